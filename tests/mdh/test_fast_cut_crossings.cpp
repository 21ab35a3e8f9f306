// Regression: a cut that moves only embedded crossings (no vertex changes
// state, no parent height moves) must still move them, inside a brick and on
// brick planes. The column-wise fast path once skipped such rows.
#include <vector>

#include <gtest/gtest.h>

#include "sim/mdh/stock.h"
#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh {
namespace {

using testing::BoxSolid;

// 2 mm cube, density 10: grid 20, bricks of 8 grid cubes (planes at 0.8, 1.6 mm).
const geom::Aabb kStock{{0, 0, 0}, {2, 2, 2}};

StockOptions options(int brick) {
  StockOptions o;
  o.brick = brick;
  o.threads = 1;
  return o;
}

// A box over the whole stock in the other two axes, up to `upTo` along `step`.
BoxSolid stepBox(int step, double upTo, double zFrom) {
  glm::dvec3 lo{-1, -1, zFrom}, hi{3, 3, 3};
  hi[step] = upTo;
  return BoxSolid(lo, hi);
}

std::vector<geom::Interval> line(const Stock& s, int axis, int iu, int iv) {
  std::vector<geom::Interval> out;
  s.solidIntervals(axis, iu, iv, out);
  return out;
}

// The grid line along `step` at the other horizontal index `across` and height z.
std::vector<geom::Interval> stepLine(const Stock& s, int step, int across, int z) {
  return step == 0 ? line(s, 0, across, z) : line(s, 1, z, across);
}

TEST(FastCutCrossings, CutMovingOnlyEmbeddedCrossingsMovesThem) {
  for (int brick : {8, 0}) {
    for (int step : {0, 1}) {
      SCOPED_TRACE(::testing::Message() << "brick " << brick << " step axis " << step);
      Stock s(kStock, options(brick));
      // A step: columns up to x (or y) 0.9 mm keep z <= 1.25, the rest stays
      // full; the step's wall crosses the lines along x (y) at 0.95 mm.
      s.cut(stepBox(step, 0.95, 1.25), {0, 0, 1});
      for (int across : {5, 8, 16})
        for (int z : {13, 16, 20}) {
          const auto before = stepLine(s, step, across, z);
          ASSERT_EQ(before.size(), 1u);
          EXPECT_NEAR(before[0].lo, 0.95, 1e-12);
          EXPECT_NEAR(before[0].hi, 2.0, 1e-12);
        }
      // Widen the step by 0.02 mm above z = 1.45: no vertex and no parent
      // height (z column) changes, only the wall's crossings at z >= 1.5.
      const CutResult r = s.cut(stepBox(step, 0.97, 1.45), {0, 0, 1});
      EXPECT_TRUE(r.touched);
      EXPECT_NEAR(r.removed_volume, 0.02 * 0.55 * 2.0, 1e-9);  // the Coons sum is exact here
      for (int across : {5, 8, 16}) {
        for (int z : {15, 16, 20}) {  // 16: a brick plane (and across 8, 16 too)
          SCOPED_TRACE(::testing::Message() << "across " << across << " z " << z);
          const auto after = stepLine(s, step, across, z);
          ASSERT_EQ(after.size(), 1u);
          EXPECT_NEAR(after[0].lo, 0.97, 1e-12);
          EXPECT_NEAR(after[0].hi, 2.0, 1e-12);
        }
        const auto below = stepLine(s, step, across, 14);  // below the second cut
        ASSERT_EQ(below.size(), 1u);
        EXPECT_NEAR(below[0].lo, 0.95, 1e-12);
      }
      // The z columns did not move.
      const int x9 = 9, x10 = 10;
      const auto c9 = step == 0 ? line(s, 2, x9, 5) : line(s, 2, 5, x9);
      const auto c10 = step == 0 ? line(s, 2, x10, 5) : line(s, 2, 5, x10);
      ASSERT_EQ(c9.size(), 1u);
      EXPECT_NEAR(c9[0].hi, 1.25, 1e-12);
      ASSERT_EQ(c10.size(), 1u);
      EXPECT_NEAR(c10[0].hi, 2.0, 1e-12);
      s.checkInvariants();
    }
  }
}

}  // namespace
}  // namespace mdhd::mdh

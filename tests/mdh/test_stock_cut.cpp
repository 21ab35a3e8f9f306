#include "sim/mdh/stock.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh {
namespace {

using testing::BoxSolid;
using testing::CylinderSolid;
using testing::SphereSolid;

const geom::Aabb kStock{{0, 0, 0}, {10, 8, 6}};

StockOptions options(int brick = 32, int threads = 1) {
  StockOptions o;
  o.density = 10;
  o.brick = brick;
  o.threads = threads;
  return o;
}

TEST(StockCut, UncutStockIsTheBox) {
  Stock s(kStock, options());
  EXPECT_DOUBLE_EQ(s.volume(), 480.0);
  EXPECT_EQ(s.stats().leaves, 4 * 3 * 2);  // bricks of 32 cubes over 100 x 80 x 60
  EXPECT_TRUE(s.isSolid({5, 4, 3}));
  EXPECT_FALSE(s.isSolid({5, 4, 6.5}));
}

TEST(StockCut, RejectsBadBoxesAndDensities) {
  EXPECT_THROW(Stock({{0, 0, 0}, {0, 1, 1}}, options()), std::invalid_argument);
  StockOptions o = options();
  o.density = -1;
  EXPECT_THROW(Stock(kStock, o), std::invalid_argument);
  o.density = std::nan("");
  EXPECT_THROW(Stock(kStock, o), std::invalid_argument);
  o.density = 1e7;
  EXPECT_THROW(Stock(kStock, o), std::invalid_argument);
  o.density = 1e4;  // 1e5 x 8e4 x 6e4 cubes: under the per-axis limit, far too many bricks
  o.brick = 32;
  try {
    Stock(kStock, o);
    ADD_FAILURE() << "a grid of 4.8e14 cubes was accepted";
  } catch (const std::invalid_argument& e) {
    // The job can change its density, not the brick: the message says so.
    EXPECT_NE(std::string(e.what()).find("lower the density"), std::string::npos) << e.what();
  }
  o.density = 100;  // one root cell of 1001 x 801 x 601 points is too large to unpack
  o.brick = 0;
  EXPECT_THROW(Stock(kStock, o), std::invalid_argument);
  o.brick = -1;
  EXPECT_THROW(Stock(kStock, o), std::invalid_argument);
  o.brick = 64;
  EXPECT_NO_THROW(Stock(kStock, o));
}

TEST(StockCut, GridAlignedPocketRemovesExactlyItsColumns) {
  for (int brick : {64, 32}) {
    Stock s(kStock, options(brick));
    const CutResult r = s.cut(BoxSolid({2, 2, 4}, {5, 6, 7}), {0, 0, 1});
    // The walls lie on grid planes and the 3-map holds their crossings: exact. The
    // squares outside the pocket's four corners were 5 grid units^3 short each
    // (24 - 0.02) until their corner columns were read off their edges' profiles.
    EXPECT_NEAR(r.removed_volume, 24.0, 1e-9);
    EXPECT_NEAR(s.volume(), 480.0 - r.removed_volume, 1e-9);
    EXPECT_TRUE(r.touched);
    EXPECT_FALSE(r.overhang);
    EXPECT_EQ(s.stats().splits(), 0);
    std::vector<geom::Interval> iv;
    s.solidIntervals(2, 35, 40, iv);  // z line through x = 3.5, y = 4
    ASSERT_EQ(iv.size(), 1u);
    EXPECT_NEAR(iv[0].lo, 0.0, 1e-12);
    EXPECT_NEAR(iv[0].hi, 4.0, 1e-12);
    s.solidIntervals(0, 40, 50, iv);  // x line through y = 4, z = 5
    ASSERT_EQ(iv.size(), 2u);
    EXPECT_NEAR(iv[0].hi, 2.0, 1e-12);
    EXPECT_NEAR(iv[1].lo, 5.0, 1e-12);
    EXPECT_NEAR(iv[1].hi, 10.0, 1e-12);
    EXPECT_FALSE(s.isSolid({3.5, 4, 5}));
    EXPECT_TRUE(s.isSolid({3.5, 4, 3.9}));
    EXPECT_NO_THROW(s.checkInvariants());
  }
}

// A tool tangent to a face on a grid line lowers that line's column (the line lies
// on the tool's surface) while every row beside it keeps its solid: the volume
// must not grow (it grew by a quarter of the drop per square: a 6 mm end mill run
// down a stock's side at density 5 "removed" -0.2 mm^3 in `mdhd check`).
TEST(StockCut, AToolTangentToAFaceRemovesNothing) {
  const geom::Aabb stock{{0, 0, -20}, {40, 30, 0}};
  for (int brick : {64, 32})
    for (int threads : {1, 2}) {
      StockOptions o;
      o.density = 5;
      o.brick = brick;
      o.threads = threads;
      Stock s(stock, o);
      double removed =
          s.cut(CylinderSolid({-3, 20, -10}, {0, 0, 1}, 3, 60), {0, 0, 1}).removed_volume;
      removed +=
          s.cut(testing::CapsuleSolid({-3, 20, -10}, {-3, 28, -10}, 3), {0, 0, 1}).removed_volume;
      removed += s.cut(SphereSolid({20, 33, -10}, 3), {0, 0, 1}).removed_volume;  // the +y face
      SCOPED_TRACE(::testing::Message() << "brick " << brick << " threads " << threads);
      EXPECT_NEAR(s.volume(), 24000.0, 1e-9 * 24000.0);
      EXPECT_NEAR(removed, 0.0, 1e-9 * 24000.0);  // each step's change agrees
      if (brick == 32 && threads == 1) {          // the check takes seconds
        EXPECT_NO_THROW(s.checkInvariants());
      }
      // The tangent line itself is on the surface; a grid step inside is solid.
      EXPECT_TRUE(s.isSolid({0.25, 20, -5}));
    }
}

TEST(StockCut, SphereFromTheTopRemovesAHemisphere) {
  Stock s(kStock, options());
  const CutResult r = s.cut(SphereSolid({5, 4, 6}, 2.0), {0, 0, 1});
  const double hemi = 2.0 / 3.0 * std::numbers::pi * 8.0;
  EXPECT_NEAR(r.removed_volume, hemi, 0.01 * hemi);
  EXPECT_NEAR(s.volume(), 480.0 - r.removed_volume, 1e-9);
  EXPECT_FALSE(s.isSolid({5, 4, 4.5}));
  EXPECT_TRUE(s.isSolid({5, 4, 3.8}));
  std::vector<geom::Interval> iv;
  s.solidIntervals(2, 50, 40, iv);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_NEAR(iv[0].hi, 4.0, 1e-12);
  s.checkInvariants();
}

TEST(StockCut, SideDrillMakesAnOverhangAndStaysExact) {
  for (bool threeWay : {true, false}) {
    StockOptions o = options();
    o.three_way = threeWay;
    Stock s(kStock, o);
    // Face the top 0.5 mm (every brick becomes a +z heightmap), then a flat
    // drill of radius 1 enters the -x face 3 mm deep at y = 4, z = 3: the
    // thesis's figure 3.8 situation.
    s.cut(BoxSolid({-1, -1, 5.5}, {11, 9, 7}), {0, 0, 1});
    EXPECT_NEAR(s.volume(), 480.0 - 40.0, 1e-9);
    const double before = s.volume();
    const CutResult r = s.cut(CylinderSolid({-1, 4, 3}, {1, 0, 0}, 1.0, 4.0), {-1, 0, 0});
    EXPECT_TRUE(r.overhang);
    const double want = std::numbers::pi * 3.0;
    // Plain heightmaps see the 5.5 mm face across their columns and the hole's
    // wall along them only through the trapezoid rule: up to h/2 times their
    // areas (2 x 3.2 x 3.2 mm, 2 pi x 1 x 3 mm) off.
    const double plainError = 0.05 * (20.5 + 2 * std::numbers::pi * 3.0);
    EXPECT_NEAR(r.removed_volume, want, threeWay ? 0.02 * want : 0.02 * want + plainError);
    EXPECT_NEAR(s.volume(), before - r.removed_volume, 1e-9);
    EXPECT_FALSE(s.isSolid({1.5, 4, 3}));
    EXPECT_TRUE(s.isSolid({1.5, 4, 4.2}));
    EXPECT_TRUE(s.isSolid({3.2, 4, 3}));
    std::vector<geom::Interval> iv;
    s.solidIntervals(0, 40, 30, iv);  // along x through the hole's axis
    ASSERT_EQ(iv.size(), 1u);
    EXPECT_NEAR(iv[0].lo, 3.0, 1e-12);
    s.solidIntervals(2, 15, 40, iv);  // along z through x = 1.5
    ASSERT_EQ(iv.size(), 2u);
    // 3-maps hold the exact crossings; plain heightmaps interpolate.
    const double tol = threeWay ? 1e-12 : 0.1;
    EXPECT_NEAR(iv[0].hi, 2.0, tol);
    EXPECT_NEAR(iv[1].lo, 4.0, tol);
    EXPECT_NEAR(iv[1].hi, 5.5, tol);
    s.checkInvariants();
  }
}

TEST(StockCut, CutOutsideTheStockTouchesNothing) {
  Stock s(kStock, options());
  const CutResult r = s.cut(SphereSolid({20, 4, 3}, 2.0), {0, 0, 1});
  EXPECT_FALSE(r.touched);
  EXPECT_EQ(r.removed_volume, 0.0);
  EXPECT_DOUBLE_EQ(s.volume(), 480.0);
}

TEST(StockCut, SolidIntervalsRejectsLinesOutsideTheGrid) {
  Stock s(kStock, options());
  std::vector<geom::Interval> iv;
  EXPECT_THROW(s.solidIntervals(2, 101, 0, iv), std::out_of_range);
  EXPECT_THROW(s.solidIntervals(0, -1, 0, iv), std::out_of_range);
}

}  // namespace
}  // namespace mdhd::mdh

namespace mdhd::mdh {
namespace {

// A solid that answers with garbage: NaN, infinite and inverted intervals.
class BrokenSolid : public geom::LineSolid {
 public:
  geom::Aabb bounds() const override { return {{2, 2, 2}, {4, 4, 7}}; }
  void lineIntervals(int, double u, double, std::vector<geom::Interval>& out) const override {
    out.push_back({std::nan(""), 3.0});
    out.push_back({5.0, 1.0});
    if (u > 3) out.push_back({-std::numeric_limits<double>::infinity(), 4.5});
  }
};

TEST(StockCut, GarbageSolidsAndDirectionsNeitherCrashNorBreakInvariants) {
  Stock s(kStock, options());
  s.cut(BrokenSolid(), {std::nan(""), 0, 0});
  s.cut(SphereSolid({5, 4, 6}, 1.0), {0, 0, 0});
  s.cut(testing::CylinderSolid({5, -1, 3}, {0, 1, 0}, 0.5, 10), {std::nan(""), 1, 0});
  EXPECT_NO_THROW(s.checkInvariants());
  EXPECT_LT(s.volume(), 480.0);
  EXPECT_GT(s.volume(), 400.0);
  geom::Aabb nanBounds{{std::nan(""), 0, 0}, {1, 1, 1}};
  struct NanBox : BrokenSolid {
    geom::Aabb b;
    geom::Aabb bounds() const override { return b; }
  } nanBox;
  nanBox.b = nanBounds;
  EXPECT_FALSE(s.cut(nanBox, {0, 0, 1}).touched);
}

}  // namespace
}  // namespace mdhd::mdh

#include "sim/mdh/three_map.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mdhd::mdh {
namespace {

const GridBox kBox{{0, 0, 0}, {4, 3, 10}};

TEST(ThreeMap, SolidCountFollowsFromTheHeight) {
  ThreeMap up(kBox, Direction{2, 1}, true);
  EXPECT_EQ(up.solidCount(10.0), 11);
  EXPECT_EQ(up.solidCount(4.0), 5);
  EXPECT_EQ(up.solidCount(4.99), 5);
  EXPECT_EQ(up.solidCount(0.0), 1);
  EXPECT_EQ(up.solidCount(-kInf), 0);
  ThreeMap down(kBox, Direction{2, -1}, true);
  EXPECT_EQ(down.solidCount(0.0), 11);
  EXPECT_EQ(down.solidCount(4.0), 7);
  EXPECT_EQ(down.solidCount(3.01), 7);
  EXPECT_EQ(down.solidCount(kInf), 0);
}

TEST(ThreeMap, SolidCountIsTheFloorAndCeilingFormulaEverywhere) {
  // The count is computed without floor/ceil: the same as the vertices k <= h (+z)
  // or k >= h (-z) of the box, for heights on, next to and far from every level.
  for (const GridBox& box : {GridBox{{0, 0, 3}, {4, 3, 40}}, GridBox{{0, 0, -7}, {4, 3, 30}}})
    for (int sign : {1, -1}) {
      const ThreeMap m(box, Direction{2, sign}, true);
      const int lo = box.lo[2], hi = box.hi[2];
      for (int k = lo - 5; k <= hi + 3; ++k)
        for (double h : {double(k), std::nextafter(double(k), -1e9), std::nextafter(double(k), 1e9),
                         k + 0.5, k - 1e-17, k + 1e-12}) {
          int expected = 0;
          for (int level = lo; level <= hi; ++level) expected += sign > 0 ? level <= h : level >= h;
          EXPECT_EQ(m.solidCount(h), expected) << sign << " " << h;
        }
      EXPECT_EQ(m.solidCount(1e300), sign > 0 ? hi - lo + 1 : 0);
      EXPECT_EQ(m.solidCount(-1e300), sign > 0 ? 0 : hi - lo + 1);
    }
}

TEST(ThreeMap, StraddledLevelsBetweenTwoColumns) {
  ThreeMap up(kBox, Direction{2, 1}, true);
  int first = 0, count = 0;
  up.straddle(7.5, 3.2, first, count);  // levels 4..7 differ
  EXPECT_EQ(first, 4);
  EXPECT_EQ(count, 4);
  up.straddle(-kInf, 1.0, first, count);
  EXPECT_EQ(first, 0);
  EXPECT_EQ(count, 2);
  ThreeMap down(kBox, Direction{2, -1}, true);
  down.straddle(7.5, 3.2, first, count);  // solid from 8 and from 4: levels 4..7
  EXPECT_EQ(first, 4);
  EXPECT_EQ(count, 4);
}

TEST(ThreeMap, TrapezoidVolumeIsExactForAPlane) {
  ThreeMap up(kBox, Direction{2, 1}, false);
  for (int iv = 0; iv < up.columnsV(); ++iv)
    for (int iu = 0; iu < up.columnsU(); ++iu) up.setHeight(iu, iv, 2.0 + 0.5 * iu);
  // 4 x 3 cross-section, height 2 + 0.5 x above z = 0: mean height 3.
  EXPECT_DOUBLE_EQ(up.volume(), 4 * 3 * 3.0);
}

// A wall between a column 100 high (the box's top) and one 22.57 high: the crossings
// of levels 23..100 all lie on the wall, equal but for their last bits. The profile runs level by
// level down the wall (sorted by position it once came in any level order and jumped across the
// wall's height: a drilled hole with a 170-degree tip read 1.2 % large).
TEST(ThreeMap, AWallsCrossingsAreOneStepWhateverTheirLastBits) {
  const ThreeMap m(GridBox{{0, 0, 0}, {4, 3, 100}}, Direction{2, 1}, true);
  const double wall = 0.4196, low = 22.57;
  std::vector<double> crossings;
  for (int level = 23; level <= 100; ++level)
    crossings.push_back(1 + wall + ((level * 7919) % 5 - 2) * 1e-15);  // edge from 1 to 2
  // Through (0, 100), down the wall from 100 to 23, then to (1, 22.57).
  const double exact = wall * 100 + (1 - wall) * (23 + low) / 2;
  EXPECT_NEAR(m.edgeIntegral(100, low, 1, crossings.data()), exact, 1e-9);
  // The other way round: the crossings of the edge from the low column to the high one.
  std::vector<double> back;
  for (int level = 23; level <= 100; ++level)
    back.push_back(1 + (1 - wall) + ((level * 104729) % 7 - 3) * 1e-15);
  EXPECT_NEAR(m.edgeIntegral(low, 100, 1, back.data()), exact, 1e-9);
}

TEST(ThreeMap, RestrictionSplitsVolumeAndKeepsEmbeddedHeights) {
  ThreeMap up(kBox, Direction{2, 1}, true);
  for (int iv = 0; iv < up.columnsV(); ++iv) {
    up.setHeight(0, iv, 8.5);
    up.setHeight(1, iv, 3.5);
  }
  // Rows of edges along x: edge 0 (heights 8.5, 3.5) straddles levels 4..8,
  // edge 1 (3.5, 10) levels 4..10; crossings where the straight profile meets them.
  std::vector<double> row;
  for (int k = 4; k <= 8; ++k) row.push_back((8.5 - k) / 5.0);
  for (int k = 4; k <= 10; ++k) row.push_back(1.0 + (k - 3.5) / 6.5);
  for (int r = 0; r < up.rowCount(0); ++r) up.row(0, r) = row;
  up.row(0, 0)[0] = 0.85;
  const double total = up.volume();
  GridBox lower = kBox, upper = kBox;
  lower.hi[2] = 6;
  upper.lo[2] = 6;
  const ThreeMap a = up.restrictedTo(lower), b = up.restrictedTo(upper);
  EXPECT_NEAR(a.volume() + b.volume(), total, 1e-12);
  EXPECT_EQ(a.height(0, 0), 6.0);          // full in the lower child
  EXPECT_EQ(b.height(1, 0), -kInf);        // empty in the upper child
  ASSERT_EQ(a.row(0, 0).size(), 3u + 3u);  // levels 4,5,6 on edge 0 and on edge 1
  EXPECT_EQ(a.row(0, 0)[0], 0.85);
  ASSERT_EQ(b.row(0, 0).size(), 3u + 5u);  // levels 6,7,8 and 6..10
  EXPECT_EQ(b.row(0, 0)[0], 0.5);
}

}  // namespace
}  // namespace mdhd::mdh

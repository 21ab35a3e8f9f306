// Two-sided 3-maps (three_map.h, thesis 7.4): columns on both sides of one map,
// their straddled levels, and the round trip through the sample grid.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "sim/mdh/good_bad_map.h"
#include "sim/mdh/sample_grid.h"
#include "sim/mdh/three_map.h"
#include "sim/mdh/two_sided_cut.h"
#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh {
namespace {

// Brute force: the levels lo..hi where exactly one of two columns is solid.
std::vector<int> straddledLevels(int f0, bool up0, int f1, bool up1, int lo, int hi) {
  auto solid = [&](int f, bool up, int k) { return up ? k < lo + f : k > hi - f; };
  std::vector<int> out;
  for (int k = lo; k <= hi; ++k)
    if (solid(f0, up0, k) != solid(f1, up1, k)) out.push_back(k);
  return out;
}

TEST(TwoSidedMap, StraddleOfEveryPairOfColumnsIsTheBruteForceOne) {
  const int lo = 3, hi = 11, n = hi - lo + 1;
  for (int f0 = 0; f0 <= n; ++f0)
    for (int f1 = 0; f1 <= n; ++f1)
      for (bool up0 : {true, false})
        for (bool up1 : {true, false}) {
          const ColumnStraddle s = columnsStraddle(f0, up0, f1, up1, lo, hi);
          const std::vector<int> expected = straddledLevels(f0, up0, f1, up1, lo, hi);
          ASSERT_EQ(s.total(), static_cast<int>(expected.size())) << f0 << up0 << " " << f1 << up1;
          for (int i = 0; i < s.total(); ++i) {
            EXPECT_EQ(s.level(i), expected[i]);
            EXPECT_EQ(s.indexOf(expected[i]), i);
          }
          EXPECT_EQ(s.indexOf(lo - 1), -1);
        }
}

// A slab x < 2 solid below z = 3.5, the rest solid above z = 5.5, with a vertical
// wall half way between x = 1 and 2: the z good-bad map has a sign conflict and no
// bad line.
SampleGrid conflictGrid() {
  const GridBox box{{0, 0, 0}, {4, 3, 8}};
  SampleGrid g(box);
  for (int z = 0; z <= 8; ++z)
    for (int y = 0; y <= 3; ++y)
      for (int x = 0; x <= 4; ++x) {
        const std::size_t i = g.index(x, y, z);
        const bool solid = x < 2 ? z <= 3 : z >= 6;
        g.state(i) = solid ? SampleGrid::kSolid : 0;
        if (z < 8 && solid != (x < 2 ? z + 1 <= 3 : z + 1 >= 6))
          g.crossing(2, i) = x < 2 ? 3.5 : 5.5;
        if (x < 4) {
          const bool next = x + 1 < 2 ? z <= 3 : z >= 6;
          if (solid != next) g.crossing(0, i) = x + 0.5;  // a wall half way
        }
      }
  return g;
}

TEST(TwoSidedMap, ASignConflictIsValidOnlyForTwoSidedMaps) {
  const SampleGrid g = conflictGrid();
  const GoodBadMap z = buildGoodBadMap(g, 2);
  EXPECT_FALSE(z.hasBad);
  EXPECT_TRUE(z.hasPositive && z.hasNegative);
  EXPECT_FALSE(z.valid());
  EXPECT_TRUE(z.valid(true));
  // Lines at x = 0, 1 are positive, at x = 2..4 negative, four of each x (y = 0..3).
  EXPECT_EQ(z.positives, 2 * 4);
  EXPECT_EQ(z.negatives, 3 * 4);
  EXPECT_EQ(z.validDirection(), (Direction{2, -1}));  // the side most lines take
}

TEST(TwoSidedMap, EncodeThenDecodeGivesTheSameStatesAndCrossings) {
  const SampleGrid g = conflictGrid();
  const ThreeMap m = encodeMap(g, Direction{2, -1}, true, true);
  EXPECT_EQ(m.flippedColumns(), 2 * 4);  // the x < 2 columns, solid below
  EXPECT_TRUE(m.flipped(0, 0));
  EXPECT_FALSE(m.flipped(3, 0));
  EXPECT_TRUE(m.columnUp(1, 2));
  EXPECT_EQ(m.columnCount(0, 0), 4);  // z = 0..3
  EXPECT_EQ(m.columnCount(4, 0), 3);  // z = 6..8
  // The x edge between columns 1 and 2 straddles z = 0..3 and z = 6..8.
  const ColumnStraddle s = m.straddleColumns(1, 0, 2, 0);
  EXPECT_EQ(s.total(), 7);
  EXPECT_EQ(s.level(3), 3);
  EXPECT_EQ(s.level(4), 6);
  const SampleGrid back = SampleGrid::decode(m, g.box());
  for (int z = 0; z <= 8; ++z)
    for (int y = 0; y <= 3; ++y)
      for (int x = 0; x <= 4; ++x) {
        const std::size_t i = g.index(x, y, z);
        ASSERT_EQ(back.solidAt(i), g.solidAt(i)) << x << " " << y << " " << z;
        for (int a = 0; a < 3; ++a) {
          const double want = g.crossing(a, i), got = back.crossing(a, i);
          if (std::isnan(want))
            EXPECT_TRUE(std::isnan(got)) << a << ": " << x << " " << y << " " << z;
          else
            EXPECT_DOUBLE_EQ(got, want) << a << ": " << x << " " << y << " " << z;
        }
      }
  // One-sided, the same grid cannot be packed in z without losing half of it.
  EXPECT_FALSE(buildGoodBadMap(g, 2).valid(false));
}

TEST(TwoSidedMap, VolumeOfColumnsOnBothSides) {
  const SampleGrid g = conflictGrid();
  const ThreeMap m = encodeMap(g, Direction{2, 1}, true, true);
  EXPECT_EQ(m.flippedColumns(), 3 * 4);
  // Per unit of y: x in [0, 1] holds 3.5 (solid to 3.5), x in [2, 4] holds 2.5 (from
  // 5.5). The square between x = 1 and 2 is the mixed one: each of its x edges is two
  // profiles through the wall's crossings at 0.5, the lower column's (3.5 at x = 1 to
  // 3 at the wall: 1.625) and the upper one's (2 at the wall to 2.5: 1.125), so the
  // square's Coons integral is (2.75 + 2.75 + 3.5 + 2.5) / 2 - (2 x 3.5 + 2 x 2.5) / 4.
  // Three units of y.
  EXPECT_NEAR(m.volume(), 3.0 * (3.5 + 2.75 + 2 * 2.5), 1e-12);
  // Nothing is lost by restricting: the two halves' volumes add up, and a half
  // holding only flipped columns is as exact as any map.
  GridBox left = g.box(), right = g.box();
  left.hi[0] = 2;
  right.lo[0] = 2;
  const ThreeMap a = m.restrictedTo(left), b = m.restrictedTo(right);
  EXPECT_NEAR(a.volume() + b.volume(), m.volume(), 1e-12);
  EXPECT_EQ(b.flippedColumns(), 3 * 4);
  EXPECT_NEAR(b.volume(), 2 * 3 * 2.5, 1e-12);
  // Restricted along the map's axis, columns that end up full or empty lose their flip.
  GridBox top = g.box();
  top.lo[2] = 6;
  const ThreeMap t = m.restrictedTo(top);
  EXPECT_EQ(t.flippedColumns(), 0);
  EXPECT_TRUE(t.allFull() == false && t.allEmpty() == false);
}

TEST(TwoSidedMap, SetHeightUnflipsAndFullColumnsAreNeverFlipped) {
  ThreeMap m(GridBox{{0, 0, 0}, {2, 2, 10}}, Direction{2, 1}, true);
  m.setColumn(1, 1, 4.5, true);  // solid from 4.5 up: levels 5..10
  EXPECT_EQ(m.flippedColumns(), 1);
  EXPECT_EQ(m.columnCount(1, 1), 6);
  EXPECT_TRUE(m.columnSolidAt(1, 1, 5));
  EXPECT_FALSE(m.columnSolidAt(1, 1, 4));
  EXPECT_NEAR(m.columnLengthAt(1, 1), 5.5, 1e-12);
  m.setHeight(1, 1, 4.5);  // back on the map's side: levels 0..4
  EXPECT_EQ(m.flippedColumns(), 0);
  EXPECT_EQ(m.columnCount(1, 1), 5);
  m.setColumn(1, 1, -3.0, true);  // solid from below the box: full, stored unflipped
  EXPECT_EQ(m.flippedColumns(), 0);
  EXPECT_TRUE(m.allFull());
}

void expectSameMap(const ThreeMap& a, const ThreeMap& b) {
  ASSERT_EQ(a.flippedColumns(), b.flippedColumns());
  for (int iv = 0; iv < a.columnsV(); ++iv)
    for (int iu = 0; iu < a.columnsU(); ++iu) {
      ASSERT_EQ(a.height(iu, iv), b.height(iu, iv)) << "column " << iu << "," << iv;
      ASSERT_EQ(a.flipped(iu, iv), b.flipped(iu, iv)) << "column " << iu << "," << iv;
    }
  for (int family = 0; family < 2; ++family)
    for (int r = 0; r < a.rowCount(family); ++r)
      ASSERT_EQ(a.row(family, r), b.row(family, r)) << "family " << family << " row " << r;
}

// twoSidedCut against unpacking the whole map, cutting it and packing it again in
// its direction: bit for bit, and its volume change that of volume(). Upright tools
// from above into the columns solid below and from below into the flipped ones.
TEST(TwoSidedMap, LocalCutMatchesTheWholeCellUnpackedBitForBit) {
  GridSpec grid;
  grid.h = 0.1;
  grid.cubes = {24, 20, 22};
  const GridBox box{{0, 0, 0}, {24, 20, 22}};
  for (int sign : {1, -1}) {
    const Direction dir{2, sign};
    // Half the map (x < 1.2 mm) carved from the side its direction leaves solid.
    SampleGrid start = SampleGrid::decode(ThreeMap(box, dir, true), box);
    const testing::BoxSolid carve(glm::dvec3(-1, -1, sign > 0 ? -1.0 : 1.4),
                                  glm::dvec3(1.2, 3, sign > 0 ? 0.8 : 3.0));
    start.applyCut(IntervalCache(grid, carve));
    ThreeMap map = encodeMap(start, dir, true, true);
    ASSERT_GT(map.flippedColumns(), 100);
    std::mt19937_64 rng(7 + sign);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int done = 0, invalid = 0;
    for (int step = 0; step < 120; ++step) {
      // From above (axis +z, tip going down) or from below.
      const bool fromAbove = unit(rng) < 0.5;
      const glm::dvec3 axis(0.2 * (unit(rng) - 0.5), 0.2 * (unit(rng) - 0.5), fromAbove ? 1 : -1);
      glm::dvec3 tip(2.4 * unit(rng), 2.0 * unit(rng), 0.0);
      const double depth = 0.5 * unit(rng);
      tip.z = fromAbove ? 2.2 - depth : depth;
      const double r = 0.15 + 0.3 * unit(rng);
      const auto tool = unit(rng) < 0.5 ? testing::ballMill(tip, glm::normalize(axis), r, 6.0)
                                        : testing::flatMill(tip, glm::normalize(axis), r, 6.0);
      const IntervalCache cache(grid, *tool);
      const ThreeMap before = map;
      double delta = 0.0;
      const TwoSidedCut result = twoSidedCut(map, cache, cache.touched(), &delta);
      if (result == TwoSidedCut::kInvalid) {
        ++invalid;
        expectSameMap(map, before);
        continue;
      }
      SampleGrid g = SampleGrid::decode(before, box);
      g.applyCut(cache);
      ThreeMap whole = encodeMap(g, dir, true, true);
      expectSameMap(map, whole);
      EXPECT_NEAR(delta, map.volume() - before.volume(), 1e-9 * (1.0 + box.pointCount()));
      done += result == TwoSidedCut::kDone;
    }
    EXPECT_GT(done, 15) << "sign " << sign;  // the comparison really ran
    EXPECT_GT(invalid, 0) << "sign " << sign;
  }
}

}  // namespace
}  // namespace mdhd::mdh

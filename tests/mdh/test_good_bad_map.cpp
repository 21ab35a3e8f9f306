#include "sim/mdh/good_bad_map.h"

#include <gtest/gtest.h>

#include "sim/mdh/isolation_splits.h"
#include "sim/mdh/region_bounds.h"

namespace mdhd::mdh {
namespace {

const GridBox kBox{{0, 0, 0}, {4, 4, 4}};

// A +z cell whose x = 2 slice lost the vertices at z = 1 and 2: a cave.
SampleGrid cave() {
  SampleGrid g = SampleGrid::solid(kBox);
  for (int y = 0; y <= 4; ++y)
    for (int z : {1, 2}) g.state(g.index(2, y, z)) = SampleGrid::kWasSolid;
  return g;
}

TEST(GoodBadMap, PixelsCountCrossingsAndSigns) {
  SampleGrid g = cave();
  const GoodBadMap z = buildGoodBadMap(g, 2);
  EXPECT_EQ(z.type[z.at(2, 3)], Pixel::kBad);  // (x 2, y 3): solid, empty, solid
  EXPECT_EQ(z.type[z.at(1, 3)], Pixel::kUnsigned);
  EXPECT_TRUE(z.hasBad);
  EXPECT_FALSE(z.valid());
  const GoodBadMap y = buildGoodBadMap(g, 1);       // pixels over (z, x)
  EXPECT_EQ(y.type[y.at(1, 2)], Pixel::kUnsigned);  // z 1, x 2: empty throughout
  EXPECT_TRUE(y.valid());
  // Cut the top of the x = 4 column: the x line at z = 4 ends solid-then-empty.
  g.state(g.index(4, 0, 4)) = 0;
  const GoodBadMap x = buildGoodBadMap(g, 0);  // pixels over (y, z)
  EXPECT_EQ(x.type[x.at(0, 4)], Pixel::kPositive);
  EXPECT_EQ(x.type[x.at(0, 1)], Pixel::kBad);
}

TEST(GoodBadMap, UnresolvedSurfaceIsWhatTheOldDirectionCannotHold) {
  SampleGrid g = cave();
  g.state(g.index(0, 0, 4)) = SampleGrid::kWasSolid;  // a plain +z notch: still holdable
  markUnresolved(g, Direction{2, 1});
  EXPECT_FALSE(g.state(g.index(0, 0, 3)) & SampleGrid::kUnresolved);
  for (int z = 0; z <= 3; ++z) EXPECT_TRUE(g.state(g.index(2, 1, z)) & SampleGrid::kUnresolved);
  EXPECT_FALSE(g.state(g.index(2, 1, 4)) & SampleGrid::kUnresolved);
  const GoodBadMap x = buildGoodBadMap(g, 0);
  EXPECT_TRUE(x.unresolved[x.at(1, 2)]);   // y 1, z 2 crosses the cave
  EXPECT_FALSE(x.unresolved[x.at(1, 4)]);  // y 1, z 4 does not
  EXPECT_TRUE(x.hasUnresolvedBad);
}

// A +z cell with a wide cave through it along y (x 1..3, z 1..3 of 0..6): the
// unresolved surface is the cave's walls, floor and roof, not the empty run
// inside it or the solid under it, so lines that cross none of its surface are
// resolved (thesis 3.2: "rays that intersect the unresolved surface").
TEST(GoodBadMap, OnlyLinesCrossingTheUnresolvedSurfaceAreUnresolved) {
  const GridBox box{{0, 0, 0}, {6, 4, 6}};
  SampleGrid g = SampleGrid::solid(box);
  for (int y = 0; y <= 4; ++y)
    for (int x = 1; x <= 3; ++x)
      for (int z = 1; z <= 3; ++z) g.state(g.index(x, y, z)) = SampleGrid::kWasSolid;
  markUnresolved(g, Direction{2, 1});
  for (int z : {0, 1, 3, 4}) EXPECT_TRUE(g.state(g.index(2, 1, z)) & SampleGrid::kUnresolved);
  EXPECT_FALSE(g.state(g.index(2, 1, 2)) & SampleGrid::kUnresolved);  // inside the cave
  EXPECT_FALSE(g.state(g.index(2, 1, 5)) & SampleGrid::kUnresolved);  // above the roof
  const GoodBadMap y = buildGoodBadMap(g, 1);                         // pixels over (z, x)
  EXPECT_FALSE(y.unresolved[y.at(2, 2)]);                             // z 2, x 2: empty all along
  EXPECT_FALSE(y.unresolved[y.at(0, 2)]);      // z 0, x 2: solid all along, under the floor
  const GoodBadMap x = buildGoodBadMap(g, 0);  // pixels over (y, z)
  EXPECT_EQ(x.type[x.at(1, 2)], Pixel::kBad);  // y 1, z 2: through both walls
  EXPECT_TRUE(x.unresolved[x.at(1, 2)]);
  EXPECT_FALSE(x.unresolved[x.at(1, 5)]);  // y 1, z 5: solid above the roof
  const GoodBadMap z = buildGoodBadMap(g, 2);
  EXPECT_TRUE(z.unresolved[z.at(2, 1)]);   // x 2, y 1: floor and roof
  EXPECT_FALSE(z.unresolved[z.at(5, 1)]);  // x 5, y 1: solid beside the cave
}

TEST(RegionBounds, TightRectanglesOfConnectedRegions) {
  GoodBadMap m;
  m.axis = 2;
  m.p0 = 10;
  m.q0 = 20;
  m.np = 6;
  m.nq = 5;
  m.type.assign(30, Pixel::kUnsigned);
  m.unresolved.assign(30, 0);
  // An L (p 0..2 at q 0, p 2 at q 1..3) and a lone pixel at (5, 4).
  for (int p : {0, 1, 2}) m.type[m.at(p, 0)] = Pixel::kBad;
  for (int q : {1, 2, 3}) m.type[m.at(2, q)] = Pixel::kBad;
  m.type[m.at(5, 4)] = Pixel::kBad;
  m.type[m.at(4, 1)] = Pixel::kPositive;
  auto rects = regionBounds(m, [&](std::size_t i) { return m.type[i] == Pixel::kBad; });
  ASSERT_EQ(rects.size(), 2u);
  EXPECT_EQ(rects[0].p0, 10);
  EXPECT_EQ(rects[0].p1, 12);
  EXPECT_EQ(rects[0].q0, 20);
  EXPECT_EQ(rects[0].q1, 23);
  EXPECT_EQ(rects[1].p0, 15);
  EXPECT_EQ(rects[1].q0, 24);
}

GoodBadMap strip(int axis, Pixel left, bool leftUnresolved, Pixel right) {
  GoodBadMap m;
  m.axis = axis;
  m.p = axisU(axis);
  m.q = axisV(axis);
  m.np = m.nq = 11;
  m.type.assign(121, Pixel::kUnsigned);
  m.unresolved.assign(121, 0);
  for (int q = 0; q <= 10; ++q) {
    for (int p = 0; p <= 2; ++p) {
      m.type[m.at(p, q)] = left;
      m.unresolved[m.at(p, q)] = leftUnresolved;
    }
    for (int p = 7; p <= 10; ++p) m.type[m.at(p, q)] = right;
  }
  m.hasBad = left == Pixel::kBad || right == Pixel::kBad;
  m.hasPositive = left == Pixel::kPositive || right == Pixel::kPositive;
  m.hasNegative = left == Pixel::kNegative || right == Pixel::kNegative;
  return m;
}

TEST(IsolationSplits, SignConflictGivesTheSeparatingInterval) {
  const GridBox cell{{0, 0, 0}, {10, 10, 10}};
  std::vector<SplitCandidate> out;
  isolationSplits(strip(2, Pixel::kNegative, true, Pixel::kPositive), 2, cell, out);
  ASSERT_EQ(out.size(), 1u);  // along y the strips overlap only at the cell's faces
  EXPECT_EQ(out[0].axis, 0);
  EXPECT_EQ(out[0].lo, 3);
  EXPECT_EQ(out[0].hi, 6);
  EXPECT_EQ(out[0].type, SplitType::kSignConflict);
  EXPECT_TRUE(out[0].complete);
}

TEST(IsolationSplits, IndirectIsolatesAGoodRegionFromBadOnes) {
  const GridBox cell{{0, 0, 0}, {10, 10, 10}};
  std::vector<SplitCandidate> out;
  isolationSplits(strip(0, Pixel::kPositive, true, Pixel::kBad), 2, cell, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].axis, 1);  // the x map's pixels run along y and z
  EXPECT_EQ(out[0].lo, 3);
  EXPECT_EQ(out[0].hi, 6);
  EXPECT_EQ(out[0].type, SplitType::kIndirect);
  // The old direction's own bad regions are left to the direct splits.
  out.clear();
  isolationSplits(strip(2, Pixel::kPositive, true, Pixel::kBad), 2, cell, out);
  EXPECT_TRUE(out.empty());
  // A resolved good region needs no isolation.
  isolationSplits(strip(0, Pixel::kPositive, false, Pixel::kBad), 2, cell, out);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace mdhd::mdh

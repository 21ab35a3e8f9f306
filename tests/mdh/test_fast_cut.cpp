// The fast path against the slow path's machinery on the same cuts: a heightmap
// cut in place (fastCut) must equal the same heightmap unpacked, cut and packed
// again in its own direction (SampleGrid::decode / applyCut / encodeMap), bit
// for bit, and its incremental volume change must equal the change of volume().
#include <random>

#include <gtest/gtest.h>

#include "sim/mdh/fast_cut.h"
#include "sim/mdh/sample_grid.h"
#include "tests/mdh/analytic_solids.h"
#include "tests/mdh/random_cuts.h"

namespace mdhd::mdh {
namespace {

void expectSameMap(const ThreeMap& a, const ThreeMap& b) {
  ASSERT_EQ(a.columnsU(), b.columnsU());
  ASSERT_EQ(a.columnsV(), b.columnsV());
  for (int iv = 0; iv < a.columnsV(); ++iv)
    for (int iu = 0; iu < a.columnsU(); ++iu)
      ASSERT_EQ(a.height(iu, iv), b.height(iu, iv)) << "column " << iu << "," << iv;
  if (!a.threeWay()) return;
  for (int family = 0; family < 2; ++family)
    for (int r = 0; r < a.rowCount(family); ++r)
      ASSERT_EQ(a.row(family, r), b.row(family, r)) << "family " << family << " row " << r;
}

// Cuts from the map's open side, most of them upright and shallow: those keep
// every column one run (fast path); tilted or deep ones often do not (overhang:
// the map must stay as it was).
void runRandomCuts(Direction dir, bool threeWay, std::uint64_t seed) {
  GridSpec grid;
  grid.h = 0.1;
  grid.cubes = {24, 20, 22};
  const GridBox box{{0, 0, 0}, {24, 20, 22}};
  const geom::Aabb mm{{0, 0, 0}, {2.4, 2.0, 2.2}};
  ThreeMap fast(box, dir, threeWay);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int done = 0, overhangs = 0;
  for (int step = 0; step < 60; ++step) {
    const bool tilted = unit(rng) < 0.3;
    glm::dvec3 axis = (tilted ? 0.6 : 0.0) * testing::randomUnit(rng);
    axis[dir.axis] = dir.sign;
    axis = glm::normalize(axis);
    glm::dvec3 tip;
    for (int a = 0; a < 3; ++a) tip[a] = mm.lo[a] + unit(rng) * (mm.hi[a] - mm.lo[a]);
    // Upright cuts reach at most 40 % into the cell from its open side.
    const double depth = (tilted ? 1.0 : 0.4) * unit(rng) * (mm.hi[dir.axis] - mm.lo[dir.axis]);
    tip[dir.axis] = dir.sign > 0 ? mm.hi[dir.axis] - depth : mm.lo[dir.axis] + depth;
    const double r = 0.2 + 0.4 * unit(rng);
    const auto tool = unit(rng) < 0.6 ? testing::ballMill(tip, axis, r, 6.0)
                                      : testing::flatMill(tip, axis, r, 6.0);
    const IntervalCache cache(grid, *tool);
    const ThreeMap before = fast;
    double delta = 0.0;
    const FastCut result = fastCut(fast, cache, cache.touched(), &delta);
    if (result == FastCut::kOverhang) {
      ++overhangs;
      expectSameMap(fast, before);
      continue;
    }
    SampleGrid g = SampleGrid::decode(before, box);
    g.applyCut(cache);
    const ThreeMap slow = encodeMap(g, dir, threeWay);
    expectSameMap(fast, slow);
    EXPECT_NEAR(delta, fast.volume() - before.volume(), 1e-9 * (1.0 + box.pointCount()));
    if (result == FastCut::kUnchanged) {
      EXPECT_EQ(delta, 0.0);
    }
    done += result == FastCut::kDone;
  }
  EXPECT_GT(done, 20);  // the comparison really ran
  EXPECT_GT(overhangs, 0);
}

TEST(FastCut, MatchesTheSlowPathBitForBitInEveryDirection) {
  for (int index = 0; index < 6; ++index) {
    SCOPED_TRACE(::testing::Message() << "direction " << index);
    runRandomCuts(directionFromIndex(index), true, 7 + index);
  }
}

TEST(FastCut, PlainHeightmapsToo) {
  runRandomCuts(Direction{2, 1}, false, 5);
  runRandomCuts(Direction{0, -1}, false, 6);
}

// Tool faces exactly on grid levels, the cell's base and top among them: the open
// interval leaves a vertex on its end solid (a zero-length run at the base: the column
// keeps that vertex), and the fast path must say so as the slow path does.
TEST(FastCut, ToolFacesOnGridLevelsMatchTheSlowPath) {
  GridSpec grid;
  grid.h = 0.1;
  grid.cubes = {12, 10, 22};
  const GridBox box{{0, 0, 0}, {12, 10, 22}};
  // z ranges in grid levels, each box over part of the columns.
  const double ranges[][2] = {{0, 30}, {0, 22}, {5, 30}, {22, 30},  {-3, 30}, {-3, 0},
                              {4, 9},  {0, 4},  {7, 22}, {7.5, 30}, {-3, 7.5}};
  int done = 0;
  for (const int sign : {1, -1})
    for (const bool threeWay : {true, false})
      for (const auto& r : ranges)
        for (const bool cutFirst : {false, true}) {
          ThreeMap map(box, Direction{2, sign}, threeWay);
          if (cutFirst) {  // heights on and between levels first
            const testing::BoxSolid first({0.25, 0.15, sign > 0 ? 1.6 : -1.0},
                                          {0.85, 0.75, sign > 0 ? 3.0 : 0.65});
            const IntervalCache c(grid, first);
            fastCut(map, c, c.touched(), nullptr);
          }
          const double lo = grid.h * r[0], hi = grid.h * r[1];
          // Mirrored for a -z map, so that the same ranges meet its open side.
          const double zlo = sign > 0 ? lo : 2.2 - hi, zhi = sign > 0 ? hi : 2.2 - lo;
          const testing::BoxSolid tool({0.3, 0.2, zlo}, {1.0, 0.9, zhi});
          const IntervalCache cache(grid, tool);
          const ThreeMap before = map;
          const FastCut result = fastCut(map, cache, cache.touched(), nullptr);
          SCOPED_TRACE(::testing::Message()
                       << "sign " << sign << " threeWay " << threeWay << " range " << r[0] << ".."
                       << r[1] << " cutFirst " << cutFirst);
          if (result == FastCut::kOverhang) {
            expectSameMap(map, before);
            continue;
          }
          SampleGrid g = SampleGrid::decode(before, box);
          g.applyCut(cache);
          expectSameMap(map, encodeMap(g, Direction{2, sign}, threeWay));
          done += result == FastCut::kDone;
        }
  EXPECT_GT(done, 30);
}

}  // namespace
}  // namespace mdhd::mdh

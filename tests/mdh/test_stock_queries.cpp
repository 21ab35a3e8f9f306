// Probes, surface area by normal direction, statistics and memory accounting.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sim/mdh/stock.h"
#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh {
namespace {

using testing::BoxSolid;
using testing::CylinderSolid;
using testing::SphereSolid;

constexpr double kPi = std::numbers::pi;
const geom::Aabb kStock{{0, 0, 0}, {10, 8, 6}};

StockOptions options(int brick) {
  StockOptions o;
  o.brick = brick;
  o.threads = 1;
  return o;
}

TEST(StockQueries, ProbeMeasuresStockInsideASolidWithoutCutting) {
  Stock s(kStock, options(32));
  const SphereSolid ball({5, 4, 3}, 1.5);
  const Overlap inside = s.probe(ball, 0.01);
  EXPECT_TRUE(inside.touched);
  EXPECT_NEAR(inside.volume, 4.0 / 3.0 * kPi * 1.5 * 1.5 * 1.5, 0.02 * 14.14);
  EXPECT_NEAR(inside.max_length, 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.volume(), 480.0);  // nothing removed
  s.cut(ball, {0, 0, 1});
  const Overlap after = s.probe(ball, 0.01);
  EXPECT_FALSE(after.touched);
  EXPECT_LT(after.volume, 0.05);
  // Grazing contact below the tolerance is not a touch.
  const Overlap graze = s.probe(SphereSolid({5, 4, 6.5}, 0.505), 0.01);
  EXPECT_FALSE(graze.touched);
}

TEST(StockQueries, RemovesMaterialLooksPastCutsStillToBeMade) {
  Stock s(kStock, options(32));
  const SphereSolid hole({5, 4, 6}, 1.5);  // a dimple in the top face
  const glm::dvec3 centre{5, 4, 6};
  glm::dvec3 hit{-1.0};
  EXPECT_TRUE(s.removesMaterial(hole, nullptr, {}, {4, 4, 6}, &hit));
  EXPECT_DOUBLE_EQ(hit.x, 4.0);  // the line asked first removes: it is the one named
  EXPECT_DOUBLE_EQ(hit.y, 4.0);
  EXPECT_GT(hit.z, 6.0 - std::sqrt(1.5 * 1.5 - 1.0));  // inside the dimple below the top
  EXPECT_LT(hit.z, 6.0);
  EXPECT_DOUBLE_EQ(s.volume(), 480.0);  // a question, not a cut
  // A cut not made yet that holds the dimple leaves it nothing to remove...
  const BoxSolid before({{3, 2, 4}, {7, 6, 7}});
  const geom::LineSolid* pending[] = {&before};
  EXPECT_FALSE(s.removesMaterial(hole, nullptr, pending, centre));
  // ... one that holds only half of it leaves the other half.
  const BoxSolid half({{3, 2, 4}, {5.05, 6, 7}});
  const geom::LineSolid* halfPending[] = {&half};
  EXPECT_TRUE(s.removesMaterial(hole, nullptr, halfPending, centre));
  // Once made, the dimple's own cut leaves nothing to remove; a region may also rule
  // the dimple's lines out.
  s.cut(hole, {0, 0, 1});
  EXPECT_FALSE(s.removesMaterial(hole, nullptr, {}, centre));
  const SphereSolid deeper({5, 4, 5.9}, 1.5);
  EXPECT_TRUE(s.removesMaterial(deeper, nullptr, {}, centre));
  geom::FreshRegion elsewhere;
  elsewhere.pieces.push_back({{{8, 0, 0}, {10, 8, 6}}});
  EXPECT_FALSE(s.removesMaterial(deeper, &elsewhere, {}, centre));
  // Touching the surface removes nothing.
  EXPECT_FALSE(s.removesMaterial(SphereSolid({2, 2, 7}, 1.0), nullptr, {}, {2, 2, 7}));
}

// A wall along a map's axis between two rows of its columns: isSolid takes it from
// the crossings on the edges across (exact at every grid line), not from the parent
// heights, whose bilinear blend put it half a grid spacing off (y = 2.0495 here).
TEST(StockQueries, IsSolidFindsAWallBetweenTwoRowsOfColumns) {
  Stock s(kStock, options(32));
  s.cut(BoxSolid({-1, 2.03, 2.0}, {11, 4.0, 4.0}), {1, 0, 0});  // a tunnel along x
  int xMaps = 0;
  s.forEachLeaf([&](const LeafView& l) { xMaps += l.map != nullptr && l.map->axis() == 0; });
  ASSERT_GT(xMaps, 0);  // the wall y = 2.03 lies along the columns of an x map
  for (double x : {1.0, 5.03, 9.37})
    for (double z : {2.15, 2.5, 3.0, 3.05, 3.85})  // not in the squares of its corners
      for (double y = 1.905; y < 2.2; y += 0.01) {
        const bool inTunnel = y > 2.03 && y < 4.0;
        EXPECT_EQ(s.isSolid({x, y, z}), !inTunnel) << x << " " << y << " " << z;
      }
}

TEST(StockQueries, AreaOfAPocketByNormalDirection) {
  Stock s(kStock, options(0));
  s.cut(BoxSolid({2, 2, 4}, {5, 6, 7}), {0, 0, 1});
  const SurfaceArea a = s.area();
  // Floor +z: 31 x 41 z lines (those on the pocket's edges included).
  EXPECT_NEAR(a.by_direction[4], 31 * 41 * 0.01, 1e-9);
  EXPECT_NEAR(a.by_direction[4], 3.0 * 4.0, 0.8);
  EXPECT_NEAR(a.by_direction[0], 2.0 * 4.0, 0.3);  // the wall at x = 2 faces +x
  EXPECT_NEAR(a.by_direction[1], 2.0 * 4.0, 0.3);
  EXPECT_NEAR(a.by_direction[2], 2.0 * 3.0, 0.3);
  EXPECT_NEAR(a.by_direction[3], 2.0 * 3.0, 0.3);
  EXPECT_EQ(a.overhang, 0.0);
}

TEST(StockQueries, OverhangAreaOfASideHole) {
  Stock s(kStock, options(32));
  s.cut(BoxSolid({-1, -1, 5.5}, {11, 9, 7}), {0, 0, 1});
  s.cut(CylinderSolid({-1, 4, 3}, {1, 0, 0}, 1.0, 4.0), {-1, 0, 0});
  // The upper half of the hole's wall faces down; projected on the xy plane
  // it is the hole's length times its diameter.
  EXPECT_NEAR(s.area().overhang, 3.0 * 2.0, 0.3);
  const Stats st = s.stats();
  EXPECT_GE(st.overhangEvents, 1);
  EXPECT_GT(st.directions[1], 0);  // -x leaves hold the hole
}

TEST(StockQueries, StatsCountLeavesAndPointerGridExactly) {
  Stock s(kStock, options(0));
  Stats st = s.stats();
  EXPECT_EQ(st.cells, 1);
  EXPECT_EQ(st.solid, 1);
  const double points = 101.0 * 81.0 * 61.0;
  EXPECT_EQ(st.pointerGridBytes, 8.0 * points);
  s.cut(BoxSolid({2, 2, 4}, {5, 6, 7}), {0, 0, 1});
  st = s.stats();
  EXPECT_EQ(st.leaves, 1);
  EXPECT_EQ(st.directions[4], 1);
  // Floor: 31 x 41 parent heights on level 40. Walls: 20 levels of embedded
  // heights on 2 x 41 edges across x and 2 x 31 across y.
  EXPECT_EQ(st.parentSamples, 31 * 41);
  EXPECT_EQ(st.embeddedSamples, 20 * (2 * 41 + 2 * 31));
  // The corner vertex (5.0, 6.0) owns an x and a y wall sample on each of the 20 levels.
  const double owners = 31 * 41 + 20 * (2 * 41 + 2 * 31) - 20;
  EXPECT_EQ(st.pointerGridBytes, 8.0 * points + 48.0 * owners);
  // Parent heights in 8 x 8 tiles, stored only where not all full: the floor's
  // columns 20..50 x 20..60 lie in tiles 2..6 x 2..7 (30 tiles). The pool grows by a
  // quarter at a time, at least 4 tiles; a slot per tile (13 x 11).
  const std::size_t tile = 64 * sizeof(double);
  const std::size_t heights = 30 * tile;
  const std::size_t embedded = std::size_t(st.embeddedSamples) * sizeof(double);
  EXPECT_GE(st.memoryBytes, heights + embedded);
  EXPECT_LE(st.memoryBytes, heights + 6 * tile + 13 * 11 * 4 + embedded + (101 + 81) * 24 + 4096);
  // The dense heights were 101 x 81 doubles.
  EXPECT_LT(st.memoryBytes, 101 * 81 * sizeof(double));
  EXPECT_DOUBLE_EQ(st.pointerGridPercent, 100.0 * double(st.memoryBytes) / st.pointerGridBytes);
}

}  // namespace
}  // namespace mdhd::mdh

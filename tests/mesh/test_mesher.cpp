// The mesher on real stocks: closed, oriented, 2-manifold, and enclosing the
// engine's volume.
#include "sim/mesh/mesher.h"

#include <gtest/gtest.h>
#include <glm/common.hpp>

#include "tests/mesh/mesh_test_support.h"

namespace mdhd::mesh {
namespace {

using testing::Ball;
using testing::Block;
using testing::expectWatertight;
using testing::meshOf;
using testing::stockOptions;

TEST(Mesher, UncutStockIsItsBox) {
  for (int brick : {0, 4, 32}) {
    mdh::Stock stock({{1, 2, 3}, {3, 3.5, 4}}, stockOptions(4, true, brick));
    const auto m = meshOf(stock);
    expectWatertight(m);
    // 8 x 6 x 4 cubes. Each leaf's solid boundary face is one fan round its rim:
    // one root cell makes 2 (6 + 4) + 2 (4 + 8) + 2 (8 + 6) rim vertices per pair of
    // faces; bricks make more, but fewer than two triangles per boundary square.
    if (brick == 0) {
      EXPECT_EQ(m.stats.triangles, 2 * (20 + 24 + 28));
    }
    EXPECT_LT(m.stats.triangles, 2 * 2 * (8 * 6 + 6 * 4 + 8 * 4));
    EXPECT_EQ(m.stats.exteriorTriangles, m.stats.triangles);
    EXPECT_EQ(m.stats.degenerateTriangles, 0);
    EXPECT_NEAR(enclosedVolume(m.mesh), 2.0 * 1.5 * 1.0, 1e-12);
    EXPECT_NEAR(surfaceArea(m.mesh), 2 * (2 * 1.5 + 1.5 + 2), 1e-12);
  }
}

TEST(Mesher, SphereCutFromTheTop) {
  mdh::Stock stock({{0, 0, 0}, {10, 8, 6}}, stockOptions(10));
  stock.cut(Ball({5, 4, 6}, 2.0), {0, 0, 1});
  const auto m = meshOf(stock);
  expectWatertight(m);
  EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.01);
}

TEST(Mesher, GridAlignedPocketHasFlatWalls) {
  // Walls on grid planes: the 3-map holds them exactly, the mesh only keeps
  // its crossings kCrossingMargin inside the edges.
  mdh::Stock stock({{0, 0, 0}, {10, 8, 6}}, stockOptions(10));
  stock.cut(Block({2, 2, 4}, {5, 6, 7}), {0, 0, 1});
  const auto m = meshOf(stock);
  expectWatertight(m);
  const double h = 0.1;
  EXPECT_NEAR(enclosedVolume(m.mesh), 480.0 - 3 * 4 * 2, surfaceArea(m.mesh) * h * kCrossingMargin);
  EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.03);
}

TEST(Mesher, MeshIsInTheWorkpieceFrame) {
  mdh::Stock stock({{10, -5, 3}, {12, -4, 4.5}}, stockOptions(8));
  stock.cut(Ball({11, -4.5, 4.5}, 0.4), {0, 0, 1});
  const auto m = meshOf(stock);
  expectWatertight(m);
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const glm::dvec3& p : m.mesh.positions()) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  EXPECT_NEAR(lo.x, 10, 1e-12);
  EXPECT_NEAR(lo.y, -5, 1e-12);
  EXPECT_NEAR(lo.z, 3, 1e-12);
  EXPECT_NEAR(hi.x, 12, 1e-12);
  EXPECT_NEAR(hi.y, -4, 1e-12);
  EXPECT_NEAR(hi.z, 4.5, 1e-12);
  const double hemisphere = 2.0 / 3.0 * testing::kPi * 0.4 * 0.4 * 0.4;
  EXPECT_NEAR(enclosedVolume(m.mesh), 2 * 1 * 1.5 - hemisphere, 0.05 * hemisphere);
}

TEST(Mesher, SideDrillOverhangIsClosedAndHoldsTheHole) {
  // A flat end mill drilling along -y into the y = 4 face, 1.5 deep: the
  // upper half of the hole overhangs, so cells turn to other directions or split.
  for (bool threeWay : {true, false}) {
    mdh::Stock stock({{0, 0, 0}, {4, 4, 4}}, stockOptions(8, threeWay, 16));
    const geom::ToolPart part = testing::toolPart(geom::ToolShape::kFlat, 1.6);
    const glm::dvec3 axis(0, 1, 0);  // tip towards the spindle
    const auto sweep =
        geom::SweptVolume::between(part, {{2, 5, 2}, axis}, {{2, 2.5, 2}, axis}, 0, 0.01);
    stock.setToolRadius(0.8);
    stock.cut(sweep, axis);
    const auto m = meshOf(stock);
    expectWatertight(m);
    const double hole = testing::kPi * 0.8 * 0.8 * 1.5;
    EXPECT_NEAR(enclosedVolume(m.mesh), 64.0 - hole, 0.03 * hole) << threeWay;
    // The engine's Coons sum and the mesh each carry their own discretisation
    // error (the tool's end face lies on the grid plane y = 2.5).
    EXPECT_NEAR(stock.volume(), 64.0 - hole, 0.03 * hole) << threeWay;
    EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.03 * hole) << threeWay;
  }
}

TEST(Mesher, PlainHeightmapStockIsClosedToo) {
  mdh::Stock stock({{0, 0, 0}, {6, 5, 3}}, stockOptions(10, false));
  const geom::ToolPart part = testing::toolPart(geom::ToolShape::kBall, 2.0);
  const glm::dvec3 up(0, 0, 1);
  stock.setToolRadius(1.0);
  stock.cut(geom::SweptVolume::between(part, {{1, 1, 2.2}, up}, {{5, 4, 1.6}, up}, 0, 0.01), up);
  const auto m = meshOf(stock);
  expectWatertight(m);
  EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.01 * surfaceArea(m.mesh) * 0.1);
}

TEST(Mesher, PlainHeightmapSurfaceIsTrueAcrossBrickPlanes) {
  // A sphere's cap cut from the top (+z maps) or the bottom (-z maps) runs through three
  // brick planes at up to 40 degrees. A column the cell beyond its surface holds empty (or
  // the cell before it full) carries no height; the crossings on such a plane interpolate
  // towards the true height in the cell that holds it: within a chord's sag of the
  // sphere, not half a grid step of slope (0.03 mm here).
  const double r = 4.5, top = 3.2;
  for (int sign : {1, -1}) {
    const glm::dvec3 c(3, 3, sign > 0 ? 6.5 : top - 6.5);
    for (int brick : {4, 0}) {
      mdh::Stock stock({{0, 0, 0}, {6, 6, top}}, stockOptions(10, false, brick));
      stock.cut(Ball(c, r), {0, 0, double(sign)});
      const auto m = meshOf(stock);
      expectWatertight(m);
      double inside = 0.0, outside = 0.0;
      int onPlanes = 0;
      for (const glm::dvec3& p : m.mesh.positions()) {
        const double d2 = (p.x - c.x) * (p.x - c.x) + (p.y - c.y) * (p.y - c.y);
        const double depth = sign > 0 ? top - p.z : p.z;  // below the cut face
        if (d2 > 2.8 * 2.8 || depth > 2.0) continue;      // the cap, not the faces beyond it
        const double err = sign * (p.z - (c.z - sign * std::sqrt(r * r - d2)));
        inside = std::max(inside, -err);  // into the removed ball
        outside = std::max(outside, err);
        for (double plane : {0.4, 0.8, 1.2, 2.0, 2.4, 2.8})
          onPlanes += std::abs(p.z - plane) < 1e-9;
      }
      EXPECT_GT(onPlanes, 100) << sign << " " << brick;
      EXPECT_LT(inside, 0.002) << sign << " " << brick;
      EXPECT_LT(outside, 0.002) << sign << " " << brick;
    }
  }
}

TEST(Mesher, PartialLeafSidesAreStripsUpToTheSurface) {
  // One leaf as tall as the stock, a +z map cut by a shallow ball from the top: each
  // side of the stock is solid from the floor to about the surface. Square by square
  // that is two triangles per grid square (50 x 21-26 on the x = 0 side); each strip
  // between two columns is one rectangle and its top squares instead.
  for (int sign : {1, -1}) {
    const glm::dvec3 c(3, 2.5, sign > 0 ? 9.0 : -6.0);
    for (bool threeWay : {true, false}) {
      mdh::Stock stock({{0, 0, 0}, {6, 5, 3}}, stockOptions(10, threeWay, 0));
      stock.cut(Ball(c, 7.5), {0, 0, double(sign)});
      const auto m = meshOf(stock);
      expectWatertight(m);
      EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.01 * surfaceArea(m.mesh) * 0.1);
      int side = 0;
      for (const auto& t : m.mesh.triangles())
        side += m.mesh.positions()[t[0]].x == 0 && m.mesh.positions()[t[1]].x == 0 &&
                m.mesh.positions()[t[2]].x == 0;
      EXPECT_GT(side, 50) << sign << threeWay;
      EXPECT_LT(side, 8 * 50) << sign << threeWay;
    }
  }
}

TEST(Mesher, RegionMeshesOnlyTheCellsItOverlaps) {
  mdh::Stock stock({{0, 0, 0}, {8, 8, 2}}, stockOptions(8, true, 8));
  stock.cut(Ball({2, 2, 2}, 1.0), {0, 0, 1});
  stock.cut(Ball({6, 6, 2}, 1.0), {0, 0, 1});
  const auto all = meshOf(stock);
  MeshOptions everything;
  everything.region = geom::Aabb{{-1, -1, -1}, {9, 9, 3}};
  EXPECT_EQ(meshOf(stock, everything).stats.triangles, all.stats.triangles);
  MeshOptions corner;
  corner.region = geom::Aabb{{1.2, 1.2, 1.5}, {2.8, 2.8, 2.5}};
  const auto part = meshOf(stock, corner);
  EXPECT_GT(part.stats.triangles, 0);
  EXPECT_LT(part.stats.triangles, all.stats.triangles / 2);
  EXPECT_LT(part.stats.leaves, all.stats.leaves);
  // Bricks are 1 mm: every triangle lies within a brick of the region.
  for (const glm::dvec3& p : part.mesh.positions())
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(p[a], (*corner.region).lo[a] - 1.0 - 1e-9);
      EXPECT_LE(p[a], (*corner.region).hi[a] + 1.0 + 1e-9);
    }
  // Inside the region the two meshes are the same.
  auto inside = [&](const testing::Meshed& m) {
    std::int64_t n = 0;
    for (const auto& t : m.mesh.triangles()) {
      bool in = true;
      for (std::uint32_t v : t)
        for (int a = 0; a < 3; ++a)
          in = in && m.mesh.positions()[v][a] >= (*corner.region).lo[a] &&
               m.mesh.positions()[v][a] <= (*corner.region).hi[a];
      n += in;
    }
    return n;
  };
  EXPECT_GT(inside(part), 100);
  EXPECT_EQ(inside(part), inside(all));
  MeshOptions bad;
  bad.region = geom::Aabb{{0, 0, 0}, {1, std::nan(""), 1}};
  EXPECT_THROW(meshOf(stock, bad), std::invalid_argument);
  bad.region = geom::Aabb{{0, 2, 0}, {1, 1, 1}};
  EXPECT_THROW(meshOf(stock, bad), std::invalid_argument);
  MeshOptions outside;
  outside.region = geom::Aabb{{20, 20, 20}, {21, 21, 21}};
  EXPECT_EQ(meshOf(stock, outside).stats.triangles, 0);
}

TEST(Mesher, FullyCutStockHasNoTriangles) {
  mdh::Stock stock({{0, 0, 0}, {1, 1, 1}}, stockOptions(4));
  stock.cut(Block({-1, -1, -1}, {2, 2, 2}), {0, 0, 1});
  const auto m = meshOf(stock);
  EXPECT_EQ(m.stats.triangles, 0);
  EXPECT_EQ(stock.volume(), 0.0);
}

}  // namespace
}  // namespace mdhd::mesh

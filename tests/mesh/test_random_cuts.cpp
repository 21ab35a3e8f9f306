// Randomised 5-axis cut sequences: whatever cells, directions and splits the
// engine makes, the mesh is closed and encloses the engine's volume.
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "tests/mesh/mesh_test_support.h"

namespace mdhd::mesh {
namespace {

using testing::expectWatertight;
using testing::meshOf;
using testing::stockOptions;

struct Case {
  bool threeWay;
  int brick;
  std::uint32_t seed;
  bool twoSided = false;
};

class RandomCuts : public ::testing::TestWithParam<Case> {};

// Moves from all sides with tilted tools of every shape.
void cutRandomly(mdh::Stock& stock, std::uint32_t seed, int moves) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const geom::ToolShape shapes[] = {geom::ToolShape::kBall, geom::ToolShape::kFlat,
                                    geom::ToolShape::kBull, geom::ToolShape::kDrill};
  for (int i = 0; i < moves; ++i) {
    const geom::ToolPart part = testing::toolPart(shapes[rng() % 4], 0.8 + 1.2 * unit(rng));
    // A main approach direction (+z mostly, sometimes a side), tilted up to 35 degrees.
    glm::dvec3 base(0, 0, 1);
    const int side = rng() % 6;
    if (side == 4) base = {1, 0, 0};
    if (side == 5) base = {0, -1, 0.2};
    auto axis = [&] {
      const glm::dvec3 w =
          glm::normalize(glm::dvec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5));
      return glm::normalize(glm::normalize(base) + 0.7 * unit(rng) * w);
    };
    auto tip = [&](const glm::dvec3& ax) {
      const glm::dvec3 c(1 + 4 * unit(rng), 1 + 4 * unit(rng), 1.5 + 2.5 * unit(rng));
      return c - ax * 0.5;  // reach a little into the stock along the axis
    };
    const glm::dvec3 a0 = axis(), a1 = axis();
    const geom::ToolPose from{tip(a0), a0}, to{tip(a1), a1};
    const auto sweep = geom::SweptVolume::between(part, from, to, 0, 0.01);
    stock.setToolRadius(0.4);
    stock.cut(sweep, glm::normalize(a0 + a1));
  }
}

TEST_P(RandomCuts, MeshIsClosedAndHoldsTheVolume) {
  const Case c = GetParam();
  mdh::StockOptions o = stockOptions(8, c.threeWay, c.brick);
  o.two_sided = c.twoSided;
  mdh::Stock stock({{0, 0, 0}, {6, 6, 4}}, o);
  cutRandomly(stock, c.seed, 8);
  if (c.twoSided) {
    EXPECT_GT(stock.stats().flippedColumns, 0);  // the cuts make some
  }
  const auto m = meshOf(stock);
  expectWatertight(m);
  const double area = surfaceArea(m.mesh);
  const double h = 1.0 / 8;
  const double diff = enclosedVolume(m.mesh) - stock.volume();
  RecordProperty("volume_difference", std::to_string(diff));
  RecordProperty("area", std::to_string(area));
  std::printf(
      "seed %u 3way %d brick %d: volume %.5f engine %.5f diff %.2e (area*h %.3f) tris %lld "
      "fallback %lld centre %lld leaves %d\n",
      c.seed, c.threeWay, c.brick, enclosedVolume(m.mesh), stock.volume(), diff, area * h,
      (long long)m.stats.triangles, (long long)m.stats.fallbackCrossings,
      (long long)m.stats.centreVertices, m.stats.leaves);
  EXPECT_LT(std::abs(diff), 0.02 * area * h);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  const int bricks[] = {0, 8, 32, 8};
  for (std::uint32_t seed = 1; seed <= 4; ++seed)
    for (bool threeWay : {true, false}) out.push_back({threeWay, bricks[seed - 1], seed});
  for (std::uint32_t seed = 1; seed <= 4; ++seed)
    out.push_back({true, bricks[seed - 1], seed, true});
  return out;
}

// The 3-map surface does not depend on where the cells are: the same cuts
// give the same mesh whatever the bricks and splits (seams are continuous).
TEST(RandomCuts, ThreeMapMeshIgnoresTheCellLayout) {
  // (Untouched boundary faces are one fan per leaf, so only the cut surface's
  // triangles are compared one for one; the area and volume cover the rest.)
  double volume[3], area[3];
  std::int64_t triangles[3];
  const int bricks[] = {0, 8, 32};
  for (int i = 0; i < 3; ++i) {
    mdh::Stock stock({{0, 0, 0}, {6, 6, 4}}, stockOptions(8, true, bricks[i]));
    cutRandomly(stock, 1, 8);
    const auto m = meshOf(stock);
    volume[i] = enclosedVolume(m.mesh);
    area[i] = surfaceArea(m.mesh);
    triangles[i] = m.stats.triangles - m.stats.exteriorTriangles;
  }
  EXPECT_NEAR(volume[1], volume[0], 1e-9);
  EXPECT_NEAR(volume[2], volume[0], 1e-9);
  EXPECT_NEAR(area[1], area[0], 1e-9);
  EXPECT_NEAR(area[2], area[0], 1e-9);
  EXPECT_EQ(triangles[1], triangles[0]);
  EXPECT_EQ(triangles[2], triangles[0]);
}

// Named from the case, so ctest's names stay the same from build to build.
INSTANTIATE_TEST_SUITE_P(Seeds, RandomCuts, ::testing::ValuesIn(cases()), [](const auto& p) {
  const Case& c = p.param;
  return "seed" + std::to_string(c.seed) +
         (c.twoSided   ? "_twosided"
          : c.threeWay ? "_threemap"
                       : "_heightmap") +
         "_brick" + std::to_string(c.brick);
});

}  // namespace
}  // namespace mdhd::mesh

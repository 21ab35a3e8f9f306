// Neighbouring leaves agree on what they share: every grid vertex on a common
// boundary has one state and every grid edge there one crossing, whatever
// the tools, directions, splits, bricks and forced cells (engine guarantee
// the mesher relies on).
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "bench/mesh/donut_surface.h"
#include "sim/mdh/shared_samples.h"
#include "sim/mdh/stock.h"
#include "sim/mdh/three_map.h"
#include "tests/mdh/analytic_solids.h"
#include "tests/mdh/random_tool_moves.h"
#include "tests/soak_seeds.h"

namespace mdhd::mdh {
namespace {

const geom::Aabb kBox{{0, 0, 0}, {6, 6, 4}};

struct Case {
  std::uint32_t seed;
  bool threeWay;
  int brick;
  double density;
  bool twoSided = true;  // StockOptions' default (3-maps only)
};

// Random 5-axis moves from every side with every tool shape; after each one
// the shared samples must agree. Returns the vertices forced cells dropped.
std::int64_t cutAndCheck(const Case& c, int count) {
  StockOptions o;
  o.density = c.density;
  o.three_way = c.threeWay;
  o.two_sided = c.twoSided;
  o.brick = c.brick;
  o.threads = 1;
  o.seed = c.seed;
  Stock stock(kBox, o);
  testing::RandomToolMoves moves(c.seed, kBox);
  for (int i = 0; i < count; ++i) {
    const testing::ToolMove m = moves.next();
    stock.setToolRadius(0.4);
    stock.cut(m.sweep, m.direction);
    const auto bad = sharedSampleDisagreements(stock, 4);
    for (const auto& d : bad) ADD_FAILURE() << "after move " << i << ": " << d.describe();
    if (!bad.empty()) break;
  }
  const Stats s = stock.stats();
  std::printf("seed %u 3way %d brick %d density %g: leaves %lld splits %lld forced %lld\n", c.seed,
              c.threeWay, c.brick, c.density, (long long)s.leaves, (long long)s.splits(),
              (long long)s.forcedVertices);
  return s.forcedVertices;
}

class SharedSamples : public ::testing::TestWithParam<Case> {};

TEST_P(SharedSamples, NeighboursAgreeAfterEveryMove) {
  cutAndCheck(GetParam(), 10);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  const int bricks[] = {0, 8, 32, 8, 0, 16};
  for (std::uint32_t seed : soak::seeds(6))
    for (bool threeWay : {true, false})
      out.push_back({seed, threeWay, bricks[(seed - 1) % 6], seed % 2 ? 8.0 : 5.0});
  return out;
}

// Named from the case, so ctest's names stay the same from build to build.
INSTANTIATE_TEST_SUITE_P(Seeds, SharedSamples, ::testing::ValuesIn(cases()), [](const auto& p) {
  const Case& c = p.param;
  return "seed" + std::to_string(c.seed) + (c.threeWay ? "_threemap" : "_heightmap") + "_brick" +
         std::to_string(c.brick) + "_density" + std::to_string(static_cast<int>(c.density));
});

// Forced one-cube cells drop vertices their neighbours hold (sub-grid
// features): the drops reach every neighbour. One-sided maps force cells on this
// seed; two-sided ones hold the same cuts without.
TEST(SharedSamples, ForcedDropsReachTheNeighbours) {
  EXPECT_GT(cutAndCheck({4, true, 8, 5.0, false}, 10), 0);
  EXPECT_GT(cutAndCheck({4, false, 8, 5.0, false}, 10), 0);
  EXPECT_EQ(cutAndCheck({4, true, 8, 5.0, true}, 10), 0);
}

// The donut of thesis figure 6.13 at density 4: its groove is about one cell
// wide, so one-sided maps force cells there (plain heightmaps and 3-maps);
// two-sided 3-maps hold it without.
TEST(SharedSamples, DonutAtDensityFour) {
  for (int kind = 0; kind < 3; ++kind) {
    StockOptions o;
    o.density = 4;
    o.three_way = kind > 0;
    o.two_sided = kind == 2;
    o.threads = 2;
    Stock stock({{0, 0, 0}, {4, 4, 1}}, o);
    mesh::bench::cutDonut(stock, mesh::bench::Donut{}, 100, 10);
    if (kind < 2)
      EXPECT_GT(stock.stats().forcedVertices, 0) << kind;
    else
      EXPECT_EQ(stock.stats().forcedVertices, 0);
    for (const auto& d : sharedSampleDisagreements(stock, 4)) ADD_FAILURE() << d.describe();
  }
}

// A pocket whose walls lie half-way between grid points: every crossing the one
// leaf stores is where the walls are, row after row (the rows' packed offsets).
TEST(SharedSamples, LeafCrossingsAreTheWalls) {
  StockOptions o;
  o.density = 10;
  o.brick = 0;
  Stock stock({{0, 0, 0}, {10, 8, 6}}, o);
  stock.cut(testing::BoxSolid({2.05, 2.05, 4.05}, {5.05, 6.05, 7}), {0, 0, 1});
  int leaves = 0;
  stock.forEachLeaf([&](const LeafView& leaf) {
    ++leaves;
    for (int z = 41; z <= 60; ++z)
      for (int y = 21; y <= 60; y += 3) {
        EXPECT_NEAR(leafCrossingAt(leaf, {20, y, z}, 0), 20.5, 1e-9) << y << " " << z;
        EXPECT_NEAR(leafCrossingAt(leaf, {50, y, z}, 0), 50.5, 1e-9) << y << " " << z;
        EXPECT_TRUE(std::isnan(leafCrossingAt(leaf, {30, y, z}, 0)));
      }
    for (int x = 21; x <= 50; x += 7) {
      EXPECT_NEAR(leafCrossingAt(leaf, {x, 20, 45}, 1), 20.5, 1e-9);
      EXPECT_NEAR(leafCrossingAt(leaf, {x, 60, 45}, 1), 60.5, 1e-9);
      EXPECT_NEAR(leafCrossingAt(leaf, {x, 30, 40}, 2), 40.5, 1e-9);
    }
  });
  EXPECT_EQ(leaves, 1);
}

// The check finds a disagreement planted on a brick boundary (it can fail).
TEST(SharedSamples, APlantedDisagreementIsFound) {
  StockOptions o;
  o.density = 10;
  o.brick = 8;
  Stock stock({{0, 0, 0}, {4, 4, 2}}, o);
  stock.cut(testing::BoxSolid({-1, -1, 1.05}, {5, 5, 3}), {0, 0, 1});
  ASSERT_TRUE(sharedSampleDisagreements(stock, 4).empty());
  bool planted = false;
  stock.forEachLeaf([&](const LeafView& leaf) {
    if (planted || leaf.map == nullptr || leaf.box.lo[0] == 0) return;
    // The floor's height on the leaf's -x face, a column its -x neighbour shares.
    auto& map = const_cast<ThreeMap&>(*leaf.map);
    ASSERT_NEAR(map.height(0, 0), 10.5, 1e-9);
    map.setHeight(0, 0, 10.75);  // the same vertices solid, another crossing
    planted = true;
  });
  ASSERT_TRUE(planted);
  // Reported from each face of the leaf that holds the column (its -x and -y faces).
  const auto bad = sharedSampleDisagreements(stock, 4);
  ASSERT_FALSE(bad.empty());
  for (const auto& d : bad) {
    EXPECT_EQ(d.axis, 2) << d.describe();
    EXPECT_EQ(d.vertex, (GridPoint{8, 0, 10})) << d.describe();
    EXPECT_NEAR(d.secondValue, 10.75, 1e-9) << d.describe();
  }
}

}  // namespace
}  // namespace mdhd::mdh

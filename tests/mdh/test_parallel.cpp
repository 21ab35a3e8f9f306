// Two threads give bit-identical results to one; the same seed gives the same stock.
#include <gtest/gtest.h>

#include "sim/mdh/stock.h"
#include "tests/mdh/analytic_solids.h"
#include "tests/mdh/random_cuts.h"

namespace mdhd::mdh {
namespace {

const geom::Aabb kBox{{0, 0, 0}, {6, 5, 4}};

struct Snapshot {
  double volume;
  Stats stats;
  std::vector<std::vector<geom::Interval>> lines;
};

Snapshot simulate(std::uint64_t seed, int threads, int brick, std::vector<Rule> rules) {
  StockOptions o;
  o.density = 10;
  o.threads = threads;
  o.brick = brick;
  o.seed = seed;
  o.ruleset = std::move(rules);
  Stock stock(kBox, o);
  for (const auto& s : testing::randomCuts(seed, kBox, 3, 5)) {
    stock.setToolRadius(s.radius);
    stock.cut(*s.solid, s.direction);
  }
  Snapshot snap{stock.volume(), stock.stats(), {}};
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i <= 40; i += 5)
      for (int j = 0; j <= 40; j += 5) {
        snap.lines.emplace_back();
        stock.solidIntervals(axis, i, j, snap.lines.back());
      }
  return snap;
}

void expectIdentical(const Snapshot& a, const Snapshot& b) {
  EXPECT_EQ(a.volume, b.volume);  // bit for bit
  EXPECT_EQ(a.stats.cells, b.stats.cells);
  EXPECT_EQ(a.stats.splits(), b.stats.splits());
  EXPECT_EQ(a.stats.memoryBytes, b.stats.memoryBytes);
  EXPECT_EQ(a.stats.embeddedSamples, b.stats.embeddedSamples);
  EXPECT_EQ(a.stats.parentSamples, b.stats.parentSamples);
  EXPECT_EQ(a.stats.leaves, b.stats.leaves);
  EXPECT_EQ(a.stats.directions, b.stats.directions);
  EXPECT_EQ(a.stats.pointerGridBytes, b.stats.pointerGridBytes);
  ASSERT_EQ(a.lines.size(), b.lines.size());
  for (std::size_t i = 0; i < a.lines.size(); ++i) {
    ASSERT_EQ(a.lines[i].size(), b.lines[i].size()) << "line " << i;
    for (std::size_t k = 0; k < a.lines[i].size(); ++k) {
      EXPECT_EQ(a.lines[i][k].lo, b.lines[i][k].lo);
      EXPECT_EQ(a.lines[i][k].hi, b.lines[i][k].hi);
    }
  }
}

TEST(Parallel, TwoThreadsMatchOneBitForBit) {
  for (std::uint64_t seed : {3u, 11u}) {
    const Snapshot one = simulate(seed, 1, 8, {Rule::kFEFS_FFS, Rule::kCTD, Rule::kSPT, Rule::kRS});
    const Snapshot two = simulate(seed, 2, 8, {Rule::kFEFS_FFS, Rule::kCTD, Rule::kSPT, Rule::kRS});
    EXPECT_GT(one.stats.splits(), 0);
    expectIdentical(one, two);
  }
}

TEST(Parallel, RandomSelectionIsReproducibleFromTheSeed) {
  const Snapshot a = simulate(5, 2, 16, {Rule::kRS});
  const Snapshot b = simulate(5, 1, 16, {Rule::kRS});
  EXPECT_GT(a.stats.splits(), 0);
  expectIdentical(a, b);
}

// Steps large enough to be shared out on the worker pool (the small random
// cuts above mostly stay on one thread): a 3 mm ball raster with tilted
// passes that undercut (slow path, splits), on bricks of 16.
Snapshot raster(int threads) {
  StockOptions o;
  o.density = 10;
  o.threads = threads;
  o.brick = 16;
  const geom::Aabb box{{0, 0, 0}, {12, 10, 6}};
  Stock stock(box, o);
  stock.setToolRadius(1.5);
  double removed = 0.0;
  for (int pass = 0; pass < 4; ++pass)
    for (double x = -1.0; x <= 13.0; x += 0.5) {
      const double y = 1.0 + 2.7 * pass;
      const glm::dvec3 axis = glm::normalize(glm::dvec3(0.0, pass % 2 ? 0.5 : -0.3, 1.0));
      const glm::dvec3 tip{x, y, 3.0 + 0.15 * pass + 0.1 * x};
      const auto tool = testing::ballMill(tip, axis, 1.5, 12.0);
      removed += stock.cut(*tool, axis).removed_volume;
    }
  stock.checkInvariants();
  EXPECT_NEAR(removed, box.hi.x * box.hi.y * box.hi.z - stock.volume(), 1e-6);
  Snapshot snap{stock.volume(), stock.stats(), {}};
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i <= 120; i += 7)
      for (int j = 0; j <= 100; j += 7) {
        snap.lines.emplace_back();
        if (i <= stock.grid().cubes[(axis + 1) % 3] && j <= stock.grid().cubes[(axis + 2) % 3])
          stock.solidIntervals(axis, i, j, snap.lines.back());
      }
  return snap;
}

TEST(Parallel, LargeStepsOnTheWorkerPoolMatchOneThreadBitForBit) {
  const Snapshot one = raster(1);
  const Snapshot two = raster(2);
  const Snapshot three = raster(3);  // more workers than cores is fine too
  EXPECT_GT(one.stats.leaves, 20);
  EXPECT_GT(one.stats.splits() + one.stats.resamples, 0);  // the slow path ran as well
  expectIdentical(one, two);
  expectIdentical(one, three);
}

// volume() and stats() add per-brick sums made on the stock's threads: they hold
// every leaf of every brick (a walk over the leaves on this thread says the same).
TEST(Parallel, VolumeAndStatsOnThreadsCountEveryLeaf) {
  for (int threads : {1, 2, 3}) {
    StockOptions o;
    o.density = 10;
    o.threads = threads;
    o.brick = 8;
    Stock stock(kBox, o);
    for (const auto& s : testing::randomCuts(7, kBox, 3, 6)) {
      stock.setToolRadius(s.radius);
      stock.cut(*s.solid, s.direction);
    }
    double leafVolume = 0.0;
    std::int64_t leaves = 0, partial = 0;
    stock.forEachLeaf([&](const LeafView& leaf) {
      ++leaves;
      if (leaf.state == CellState::kSolid)
        leafVolume += double(leaf.box.cubes(0)) * leaf.box.cubes(1) * leaf.box.cubes(2);
      else if (leaf.map)
        leafVolume += leaf.map->volume(), ++partial;
    });
    const double h3 = 0.1 * 0.1 * 0.1;
    EXPECT_NEAR(stock.volume(), leafVolume * h3, 1e-9 * leafVolume * h3) << threads;
    const Stats st = stock.stats();
    EXPECT_EQ(st.leaves, leaves) << threads;
    std::int64_t directions = 0;
    for (std::int64_t d : st.directions) directions += d;
    EXPECT_EQ(directions, partial) << threads;
    EXPECT_GT(partial, 10) << threads;
  }
}

}  // namespace
}  // namespace mdhd::mdh

// Two threads give bit-identical results to one; the same seed gives the same stock.
#include <gtest/gtest.h>

#include "sim/mdh/stock.h"
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

}  // namespace
}  // namespace mdhd::mdh

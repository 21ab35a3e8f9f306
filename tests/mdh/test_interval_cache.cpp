#include "sim/mdh/interval_cache.h"

#include <atomic>

#include <gtest/gtest.h>

#include "sim/mdh/stock.h"
#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh {
namespace {

// Counts how often each line is asked for.
class CountingSolid : public geom::LineSolid {
 public:
  explicit CountingSolid(const geom::LineSolid& inner) : inner_(inner) {}
  geom::Aabb bounds() const override { return inner_.bounds(); }
  void lineIntervals(int axis, double u, double v,
                     std::vector<geom::Interval>& out) const override {
    ++calls;
    inner_.lineIntervals(axis, u, v, out);
  }
  mutable std::atomic<int> calls{0};

 private:
  const geom::LineSolid& inner_;
};

GridSpec grid() {
  GridSpec g;
  g.h = 0.1;
  g.cubes = {100, 80, 60};
  return g;
}

TEST(IntervalCache, BoundsBecomeAVertexBoxClippedToTheStock) {
  const GridSpec g = grid();
  testing::SphereSolid sphere({0.55, 4.0, 5.9}, 0.3);
  IntervalCache cache(g, sphere);
  EXPECT_EQ(cache.touched().lo, (std::array<int, 3>{2, 37, 56}));
  EXPECT_EQ(cache.touched().hi, (std::array<int, 3>{9, 43, 60}));
  testing::SphereSolid away({50, 4, 3}, 1.0);
  EXPECT_TRUE(IntervalCache(g, away).touched().empty());
}

TEST(IntervalCache, LinesAreInGridUnitsSnappedAndComputedOncePerLine) {
  const GridSpec g = grid();
  testing::BoxSolid box({1.0, 2.0, 3.0}, {2.0, 3.0, 4.0});
  CountingSolid counting(box);
  IntervalCache cache(g, counting);
  const auto line = cache.line(2, 15, 25);  // z line through x = 1.5, y = 2.5
  ASSERT_EQ(line.size(), 1u);
  EXPECT_EQ(line[0].lo, 30.0);  // 3.0 / 0.1 snapped onto the grid plane
  EXPECT_EQ(line[0].hi, 40.0);
  EXPECT_EQ(counting.calls, 1);  // only the line asked for, not its row
  for (int k = 0; k < 3; ++k) EXPECT_EQ(cache.line(2, 15, 25).size(), 1u);
  EXPECT_EQ(counting.calls, 1);
  for (int i = 10; i <= 20; ++i) cache.line(2, i, 25);
  EXPECT_EQ(counting.calls, 11);
  EXPECT_EQ(cache.queries(), 11u);
  EXPECT_TRUE(cache.line(2, 5, 25).empty());  // outside the bounds: no call at all
  EXPECT_EQ(counting.calls, 11);
}

TEST(IntervalCache, AReusedStoreForgetsThePreviousStep) {
  const GridSpec g = grid();
  LineStore store;
  testing::BoxSolid first({1.0, 2.0, 3.0}, {2.0, 3.0, 4.0});
  testing::BoxSolid second({1.0, 2.0, 3.5}, {2.0, 3.0, 5.0});
  {
    IntervalCache cache(g, first, &store);
    ASSERT_EQ(cache.line(2, 15, 25).size(), 1u);
    EXPECT_EQ(cache.line(2, 15, 25)[0].lo, 30.0);
  }
  IntervalCache cache(g, second, &store);
  const auto line = cache.line(2, 15, 25);  // the same slot: recomputed, not the old one
  ASSERT_EQ(line.size(), 1u);
  EXPECT_EQ(line[0].lo, 35.0);
  EXPECT_EQ(line[0].hi, 50.0);
  EXPECT_EQ(cache.queries(), 1u);
}

// A solid whose lines cross it three times: more intervals than a slot holds inline.
class CombSolid : public geom::LineSolid {
 public:
  geom::Aabb bounds() const override { return {{0, 0, 0}, {1, 1, 1}}; }
  void lineIntervals(int, double, double, std::vector<geom::Interval>& out) const override {
    out.push_back({0.6, 0.8});  // unsorted and overlapping on purpose
    out.push_back({0.0, 0.2});
    out.push_back({0.3, 0.5});
    out.push_back({0.45, 0.55});
  }
};

TEST(IntervalCache, ManyIntervalsAreSortedMergedAndKept) {
  const GridSpec g = grid();
  CombSolid comb;
  IntervalCache cache(g, comb, nullptr, 1u << 0);
  const auto line = cache.line(0, 3, 4);
  ASSERT_EQ(line.size(), 3u);
  EXPECT_NEAR(line[0].hi, 2.0, 1e-12);
  EXPECT_NEAR(line[1].lo, 3.0, 1e-12);
  EXPECT_NEAR(line[1].hi, 5.5, 1e-12);
  EXPECT_NEAR(line[2].lo, 6.0, 1e-12);
  EXPECT_THROW(cache.line(2, 3, 4), std::logic_error);  // made for x lines only
}

TEST(IntervalCache, AStockCutAsksEachLineAtMostOnce) {
  testing::SphereSolid sphere({3.0, 2.5, 4.0}, 1.2);
  CountingSolid counting(sphere);
  StockOptions o;
  o.brick = 8;  // many cells share the lines
  o.threads = 2;
  Stock stock({{0, 0, 0}, {6, 5, 4}}, o);
  stock.cut(counting, {0, 0, 1});
  // The touched box has 25 x 25 x 13 vertices; three families of lines.
  EXPECT_GT(counting.calls, 0);
  EXPECT_LE(counting.calls, 25 * 13 + 13 * 25 + 25 * 25);
}

}  // namespace
}  // namespace mdhd::mdh

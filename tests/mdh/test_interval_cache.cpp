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

TEST(IntervalCache, LinesAreInGridUnitsSnappedAndComputedOncePerRow) {
  const GridSpec g = grid();
  testing::BoxSolid box({1.0, 2.0, 3.0}, {2.0, 3.0, 4.0});
  CountingSolid counting(box);
  IntervalCache cache(g, counting);
  const auto line = cache.line(2, 15, 25);  // z line through x = 1.5, y = 2.5
  ASSERT_EQ(line.size(), 1u);
  EXPECT_EQ(line[0].lo, 30.0);  // 3.0 / 0.1 snapped onto the grid plane
  EXPECT_EQ(line[0].hi, 40.0);
  const int afterFirst = counting.calls;
  EXPECT_EQ(afterFirst, 11);  // the row x = 1.0 .. 2.0 at y = 2.5
  for (int i = 10; i <= 20; ++i) cache.line(2, i, 25);
  EXPECT_EQ(counting.calls, afterFirst);
  EXPECT_EQ(cache.queries(), std::size_t(afterFirst));
  EXPECT_TRUE(cache.line(2, 5, 25).empty());  // outside the bounds: no call at all
  EXPECT_EQ(counting.calls, afterFirst);
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

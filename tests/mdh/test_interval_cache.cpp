#include "sim/mdh/interval_cache.h"

#include <atomic>
#include <cmath>
#include <cstring>
#include <set>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_part.h"
#include "sim/mdh/stock.h"
#include "tests/geometry/geometry_test_support.h"
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
    if (axis >= 0 && axis < 3) ++singles[axis];
    inner_.lineIntervals(axis, u, v, out);
  }
  // Rows go to the inner solid's own row form (a sweep's body-by-body pass), each
  // line counted as a call.
  void rowIntervals(int axis, std::span<const double> us, double v,
                    std::vector<geom::Interval>& out, std::span<std::size_t> ends) const override {
    calls += static_cast<int>(us.size());
    ++rows;
    inner_.rowIntervals(axis, us, v, out, ends);
  }
  void linesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                      std::vector<geom::Interval>& out,
                      std::span<std::size_t> ends) const override {
    calls += static_cast<int>(us.size());
    ++batches;
    if (axis >= 0 && axis < 3) batched[axis] += static_cast<int>(us.size());
    inner_.linesIntervals(axis, us, vs, out, ends);
  }
  bool rowsPay(int axis) const override { return inner_.rowsPay(axis); }
  bool linesPay(int axis) const override { return inner_.linesPay(axis); }
  bool prismBand(int& axis, double& lo, double& hi) const override {
    return inner_.prismBand(axis, lo, hi);
  }
  mutable std::atomic<int> calls{0};
  mutable std::atomic<int> rows{0};
  mutable std::atomic<int> batches{0};
  mutable std::atomic<int> singles[3] = {0, 0, 0};  // lines asked one by one, per axis
  mutable std::atomic<int> batched[3] = {0, 0, 0};  // lines asked through linesIntervals

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

// Two intervals (what fits a slot inline), in whichever order and overlap the
// line's position asks for: x picks the case.
class PairSolid : public geom::LineSolid {
 public:
  geom::Aabb bounds() const override { return {{0, 0, 0}, {1, 1, 1}}; }
  void lineIntervals(int, double y, double, std::vector<geom::Interval>& out) const override {
    const int c = static_cast<int>(std::lround(y * 10));
    if (c == 1) out.insert(out.end(), {{0.6, 0.8}, {0.1, 0.2}});           // unsorted
    if (c == 2) out.insert(out.end(), {{0.3, 0.5}, {0.1, 0.4}});           // unsorted, overlapping
    if (c == 3) out.insert(out.end(), {{0.1, 0.3}, {0.3, 0.6}});           // touching
    if (c == 4) out.insert(out.end(), {{0.5, 0.2}, {std::nan(""), 0.9}});  // both dropped
    if (c == 5) out.insert(out.end(), {{0.7, 0.9}, {0.5, 0.5}});           // empty one dropped
  }
};

TEST(IntervalCache, TwoIntervalsAreSortedMergedAndCleanedInTheSlot) {
  const GridSpec g = grid();
  PairSolid pair;
  IntervalCache cache(g, pair, nullptr, 1u << 0);
  const auto spans = [&](int iy) {
    const auto l = cache.line(0, iy, 4);
    return std::vector<Span>(l.begin(), l.end());
  };
  const auto near = [](const std::vector<Span>& got, std::vector<Span> want) {
    if (got.size() != want.size()) return false;
    for (std::size_t i = 0; i < got.size(); ++i)
      if (std::abs(got[i].lo - want[i].lo) > 1e-9 || std::abs(got[i].hi - want[i].hi) > 1e-9)
        return false;
    return true;
  };
  EXPECT_TRUE(near(spans(1), {{1, 2}, {6, 8}}));
  EXPECT_TRUE(near(spans(2), {{1, 5}}));
  EXPECT_TRUE(near(spans(3), {{1, 6}}));
  EXPECT_TRUE(spans(4).empty());
  EXPECT_TRUE(near(spans(5), {{7, 9}}));
}

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

TEST(IntervalCache, LinesInTheToolsPrismBandShareOneQueryAndMatchTheirOwn) {
  // A vertical ball swept sideways: every x and y line above its ball part asks the
  // one line at the band's first level, and gets what it would have got itself.
  const GridSpec g = grid();
  const geom::ToolPart part = geom::makeToolPart(
      geom::testing::makeTool(geom::ToolShape::kBall, 2.0, 3.0), geom::ToolPartKind::kCutter);
  const glm::dvec3 z(0, 0, 1);
  const geom::SweptVolume sweep =
      geom::SweptVolume::between(part, {{4.0, 3.9, 2.0}, z}, {{5.1, 4.3, 1.8}, z}, 0, 0.01);
  CountingSolid counting(sweep);
  IntervalCache cache(g, counting);
  const IntervalCache::PrismBand& band = cache.prismBand();
  ASSERT_EQ(band.axis, 2);
  // From the highest ball centre (z 2 + 1) to the lowest cylinder top (z 1.8 + 3).
  EXPECT_EQ(band.lo, static_cast<int>(std::ceil(g.toGrid(2, 2.0 + 1.0))));
  EXPECT_EQ(band.hi, static_cast<int>(std::floor(g.toGrid(2, 1.8 + 3.0))));
  ASSERT_GE(band.hi - band.lo, 17);
  const GridBox& t = cache.touched();
  std::vector<geom::Interval> own;
  std::size_t lines = 0;
  for (int axis : {0, 1}) {
    const int u = axisU(axis), v = axisV(axis);
    for (int iv = t.lo[v]; iv <= t.hi[v]; ++iv)
      for (int iu = t.lo[u]; iu <= t.hi[u]; ++iu, ++lines) {
        own.clear();
        sweep.lineIntervals(axis, g.toMm(u, iu), g.toMm(v, iv), own);
        std::erase_if(own, [&](const geom::Interval& i) {  // grazing chords (kMinToolSpan)
          return g.toGrid(axis, i.hi) - g.toGrid(axis, i.lo) <= kMinToolSpan;
        });
        const auto line = cache.line(axis, iu, iv);
        ASSERT_EQ(line.size(), own.size()) << axis << " " << iu << " " << iv;
        for (std::size_t k = 0; k < own.size(); ++k) {
          EXPECT_NEAR(line[k].lo, g.toGrid(axis, own[k].lo), 1e-9);
          EXPECT_NEAR(line[k].hi, g.toGrid(axis, own[k].hi), 1e-9);
        }
      }
  }
  // All but the first of the band's levels cost nothing.
  const std::size_t across = static_cast<std::size_t>(t.points(0) + t.points(1));
  EXPECT_EQ(cache.queries(), lines - static_cast<std::size_t>(band.hi - band.lo) * across);
}

// A chain of short moves of a vertical ball, as a 3-axis batch cuts it.
geom::SweptVolume ballChain() {
  const geom::ToolPart part = geom::makeToolPart(
      geom::testing::makeTool(geom::ToolShape::kBall, 2.0, 3.0), geom::ToolPartKind::kCutter);
  const glm::dvec3 z(0, 0, 1);
  std::vector<geom::ToolPose> poses;
  for (int j = 0; j <= 8; ++j)
    poses.push_back({{3.0 + 0.31 * j, 3.7 + 0.02 * j * j, 2.0 - 0.05 * j + 0.01 * j * j}, z});
  return geom::SweptVolume::chainOfTranslations(part, poses);
}

bool sameSpans(std::span<const Span> a, std::span<const Span> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Span)) == 0;
}

// After a batch fill of the lines `inFill(iu, iv)` picks (in the box) through
// `counting`: the fill asked each such line once (a band's lines are its first
// level's), and every line of the box then gives what a plain cache gives, the
// fill's lines for no further query and the others for one each.
template <class InFill>
void expectFilledOnce(const IntervalCache& filled, const IntervalCache& single,
                      const CountingSolid& counting, int axis, InFill inFill) {
  const int fillQueries = counting.calls;
  const GridBox& t = filled.touched();
  const int u = axisU(axis), v = axisV(axis);
  const IntervalCache::PrismBand& band = filled.prismBand();
  ASSERT_EQ(band.axis, 2);  // the test is of lines in the band too
  const auto key = [&](int iu, int iv) {
    if (band.axis == u && band.holds(iu)) iu = band.lo;
    if (band.axis == v && band.holds(iv)) iv = band.lo;
    return std::pair(iu, iv);
  };
  std::set<std::pair<int, int>> known;
  for (int iv = t.lo[v]; iv <= t.hi[v]; ++iv)
    for (int iu = t.lo[u]; iu <= t.hi[u]; ++iu)
      if (inFill(iu, iv)) known.insert(key(iu, iv));
  EXPECT_EQ(static_cast<std::size_t>(fillQueries), known.size());  // each once, none outside
  for (int iv = t.lo[v]; iv <= t.hi[v]; ++iv)
    for (int iu = t.lo[u]; iu <= t.hi[u]; ++iu) {
      const int before = counting.calls;
      const auto got = filled.line(axis, iu, iv);
      EXPECT_EQ(counting.calls - before, known.insert(key(iu, iv)).second ? 1 : 0)
          << axis << " " << iu << " " << iv;
      EXPECT_TRUE(sameSpans(got, single.line(axis, iu, iv))) << axis << " " << iu << " " << iv;
    }
  EXPECT_EQ(filled.queries(), single.queries());
}

TEST(IntervalCache, ARowFillGivesEveryLineWhatLineWouldOnceAndOnlyTheLinesAsked) {
  const GridSpec g = grid();
  const geom::SweptVolume sweep = ballChain();
  for (int mode = 0; mode < 6; ++mode) {
    const int axis = mode % 3;
    CountingSolid counting(sweep);
    IntervalCache rows(g, counting), single(g, sweep);
    rows.setShared(mode < 3);  // one thread's cache claims its lines without atomics
    const GridBox& t = rows.touched();
    const int u = axisU(axis), v = axisV(axis);
    // Every other line of each row, and one row twice: the second fill asks nothing.
    for (int iv = t.lo[v] - 1; iv <= t.hi[v] + 1; ++iv) {
      std::vector<int> ius;
      for (int iu = t.lo[u] - 2; iu <= t.hi[u] + 2; iu += 2) ius.push_back(iu);
      rows.fillRow(axis, iv, ius);
      if (iv == t.lo[v] + 3) rows.fillRow(axis, iv, ius);
    }
    EXPECT_GT(counting.rows, 0);
    expectFilledOnce(rows, single, counting, axis,
                     [&](int iu, int) { return (iu - (t.lo[u] - 2)) % 2 == 0; });
  }
}

TEST(IntervalCache, RowSpansAreWhatLineGivesWithNoSlotFilled) {
  const GridSpec g = grid();
  const geom::SweptVolume sweep = ballChain();
  for (int axis = 0; axis < 3; ++axis) {
    CountingSolid counting(sweep);
    IntervalCache own(g, counting), single(g, sweep);
    const GridBox& t = own.touched();
    const int u = axisU(axis), v = axisV(axis);
    int lines = 0, nonEmpty = 0;
    for (int iv = t.lo[v] - 1; iv <= t.hi[v] + 1; ++iv) {
      std::vector<int> ius;  // every other line, some outside the box
      for (int iu = t.lo[u] - 2; iu <= t.hi[u] + 2; iu += 2) ius.push_back(iu);
      std::vector<Span> spans;
      std::vector<std::size_t> ends;
      own.rowSpans(axis, iv, ius, spans, ends);
      ASSERT_EQ(ends.size(), ius.size());
      for (std::size_t j = 0; j < ius.size(); ++j) {
        const std::size_t from = j == 0 ? 0 : ends[j - 1];
        const auto want = single.line(axis, ius[j], iv);
        ASSERT_EQ(ends[j] - from, want.size()) << axis << " " << ius[j] << " " << iv;
        for (std::size_t k = 0; k < want.size(); ++k) {
          // The same bits: the same row kernel as a fill, cleaned as a slot is.
          EXPECT_EQ(std::memcmp(&spans[from + k], &want[k], sizeof(Span)), 0);
        }
        ++lines;
        nonEmpty += !want.empty();
      }
    }
    EXPECT_GT(nonEmpty, 20) << axis;
    EXPECT_GT(lines, nonEmpty) << axis;    // lines outside the box answer empty
    EXPECT_EQ(own.queries(), 0u) << axis;  // no slot was filled
    EXPECT_EQ(counting.singles[axis], 0) << axis;
  }
}

TEST(IntervalCache, ALinesFillGivesEveryLineWhatLineWouldOnceAndOnlyTheLinesAsked) {
  const GridSpec g = grid();
  const geom::SweptVolume sweep = ballChain();
  for (int mode = 0; mode < 6; ++mode) {
    const int axis = mode % 3;
    CountingSolid counting(sweep);
    IntervalCache lines(g, counting), single(g, sweep);
    lines.setShared(mode < 3);
    const GridBox& t = lines.touched();
    const int u = axisU(axis), v = axisV(axis);
    // Lines of a checkerboard (some outside the box), column by column, in one fill;
    // then the same again, which asks nothing.
    std::vector<int> ius, ivs;
    for (int iu = t.hi[u] + 2; iu >= t.lo[u] - 2; --iu)
      for (int iv = t.lo[v] - 1; iv <= t.hi[v] + 1; ++iv)
        if ((iu + iv) % 2 == 0) ius.push_back(iu), ivs.push_back(iv);
    lines.fillLines(axis, ius, ivs);
    lines.fillLines(axis, ius, ivs);
    EXPECT_EQ(counting.batches, 1);
    expectFilledOnce(lines, single, counting, axis,
                     [](int iu, int iv) { return (iu + iv) % 2 == 0; });
  }
}

TEST(IntervalCache, LinesFillsFromTwoThreadsShareTheLinesAndAgree) {
  const GridSpec g = grid();
  const geom::SweptVolume sweep = ballChain();
  ASSERT_TRUE(sweep.linesPay(0) && sweep.linesPay(1));  // through the sweep's own batch form
  CountingSolid counting(sweep);
  IntervalCache shared(g, counting), single(g, sweep);
  const GridBox& t = shared.touched();
  auto work = [&](int first) {
    for (int axis = 0; axis < 2; ++axis) {
      const int u = axisU(axis), v = axisV(axis);
      for (int iv = t.lo[v]; iv <= t.hi[v]; iv += 4) {
        std::vector<int> ius, ivs;
        for (int dv = 0; dv < 4; ++dv)
          for (int iu = t.lo[u] + (first + dv) % 3; iu <= t.hi[u]; ++iu)
            ius.push_back(iu), ivs.push_back(iv + dv);
        shared.fillLines(axis, ius, ivs);
        for (int iu = t.lo[u]; iu <= t.hi[u]; iu += 5) shared.line(axis, iu, iv);
      }
    }
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  const IntervalCache::PrismBand& band = shared.prismBand();
  std::set<std::tuple<int, int, int>> distinct;
  for (int axis = 0; axis < 2; ++axis) {
    const int u = axisU(axis), v = axisV(axis);
    for (int iv = t.lo[v]; iv <= t.hi[v]; ++iv)
      for (int iu = t.lo[u]; iu <= t.hi[u]; ++iu) {
        EXPECT_TRUE(sameSpans(shared.line(axis, iu, iv), single.line(axis, iu, iv)))
            << axis << " " << iu << " " << iv;
        const int ku = band.axis == u && band.holds(iu) ? band.lo : iu;
        const int kv = band.axis == v && band.holds(iv) ? band.lo : iv;
        distinct.insert({axis, ku, kv});
      }
  }
  // Every line computed exactly once, whichever thread or path got there first.
  EXPECT_EQ(counting.calls, static_cast<int>(distinct.size()));
}

// A 3-axis batch over a stock it has cut before (z maps, cut by the fast path): the x
// and y lines the crossings need come through fastCut's gathering, in batches, all of
// them. A line the gathering missed would still be asked, one by one: this catches the
// gathering falling out of step with what the loop asks (which costs time, not answers).
TEST(IntervalCache, AFastCutAsksItsCrossingLinesInBatches) {
  const geom::SweptVolume first = ballChain();
  const geom::ToolPart part = geom::makeToolPart(
      geom::testing::makeTool(geom::ToolShape::kBall, 2.0, 3.0), geom::ToolPartKind::kCutter);
  std::vector<geom::ToolPose> poses;
  for (int j = 0; j <= 8; ++j)
    poses.push_back({{3.1 + 0.3 * j, 3.9 + 0.01 * j * j, 1.9 - 0.04 * j}, {0, 0, 1}});
  const geom::SweptVolume second = geom::SweptVolume::chainOfTranslations(part, poses);
  ASSERT_TRUE(second.linesPay(0) && second.linesPay(1));
  for (int threads : {1, 2}) {
    StockOptions o;
    o.brick = 8;
    o.threads = threads;
    Stock stock({{0, 0, 0}, {7, 7, 4}}, o);
    stock.cut(first, {0, 0, 1});
    CountingSolid counting(second);
    stock.cut(counting, {0, 0, 1});
    const int batched = counting.batched[0] + counting.batched[1];
    const int singles = counting.singles[0] + counting.singles[1];
    EXPECT_GT(batched, 500) << threads;
    // One thread: every line batched. Two: a line on a brick face was once seen asked
    // alone (1 of 801, CI under ASan, session 22): which thread's gathering covers it
    // depends on timing. Still at most a few lines, or the gathering is out of step.
    const int allowed = threads == 1 ? 0 : (batched + singles) / 100;
    EXPECT_LE(singles, allowed) << threads << " threads: " << singles << " of " << batched + singles
                                << " lines asked one by one";
  }
}

TEST(IntervalCache, RowFillsFromTwoThreadsShareTheLinesAndAgree) {
  const GridSpec g = grid();
  const geom::SweptVolume sweep = ballChain();
  CountingSolid counting(sweep);
  IntervalCache shared(g, counting), single(g, sweep);
  const GridBox& t = shared.touched();
  auto work = [&](int first) {
    for (int round = 0; round < 2; ++round)
      for (int iv = t.lo[1]; iv <= t.hi[1]; ++iv) {
        std::vector<int> ius;
        for (int iu = t.lo[0] + (first + iv + round) % 3; iu <= t.hi[0]; ++iu) ius.push_back(iu);
        shared.fillRow(2, iv, ius);
        for (int iu = t.lo[0]; iu <= t.hi[0]; iu += 5) shared.line(2, iu, iv);
      }
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  std::size_t lines = 0;
  for (int iv = t.lo[1]; iv <= t.hi[1]; ++iv)
    for (int iu = t.lo[0]; iu <= t.hi[0]; ++iu, ++lines)
      EXPECT_TRUE(sameSpans(shared.line(2, iu, iv), single.line(2, iu, iv))) << iu << " " << iv;
  EXPECT_EQ(counting.calls, static_cast<int>(lines));  // every line computed exactly once
}

// A ball drill along x on a grid line, its radius a whole number of grid steps: the z
// lines at its sides graze the shank and their chords are rounding noise (1e-7 grid
// units, different from line to line). Dropped (kMinToolSpan), they remove no vertex,
// so the hole is one run of every x column and the cube takes it without a split
// (kept, the side column flickered between removed and kept: thesis case A2 split).
TEST(IntervalCache, GrazingChordsRemoveNothing) {
  const geom::ToolPart part = geom::makeToolPart(
      geom::testing::makeTool(geom::ToolShape::kBall, 0.3, 6.0), geom::ToolPartKind::kCutter);
  const glm::dvec3 axis(-1, 0, 0);
  const geom::SweptVolume drill =
      geom::SweptVolume::between(part, {{-0.3, 1, 1}, axis}, {{1, 1, 1}, axis}, 10, 1e-3);
  StockOptions o;
  o.density = 100;
  o.brick = 0;
  o.threads = 1;
  Stock stock({{0, 0, 0}, {2, 2, 2}}, o);
  const CutResult r = stock.cut(drill, axis);
  EXPECT_EQ(r.splits, 0);
  EXPECT_EQ(stock.stats().leaves, 1);
  // The side lines tangent to the shank (y = 1 - 0.15) lose nothing at z = 1.
  std::vector<geom::Interval> out;
  stock.solidIntervals(0, 85, 100, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].lo, 0.0);
  EXPECT_DOUBLE_EQ(out[0].hi, 2.0);
}

}  // namespace
}  // namespace mdhd::mdh

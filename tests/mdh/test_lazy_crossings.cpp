// Lazy crossings (sim/mdh/lazy_crossings.h): batches and steps cut with a shared solid leave
// the crossings across z maps to be computed later. Whatever is asked in between and
// in whatever order, the stock must be the one the eager cuts leave, to the bit: every
// grid line's intervals, the stats, the volume.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_fresh_region.h"
#include "sim/mdh/fast_cut.h"
#include "sim/mdh/lazy_crossings.h"
#include "sim/mdh/stock.h"
#include "tests/mdh/analytic_solids.h"
#include "tests/mdh/random_cuts.h"
#include "tests/mdh/random_tool_moves.h"
#include "tests/mdh/stock_lines.h"
#include "tests/mdh/wavy_rows.h"

namespace mdhd::mdh {
namespace {

const geom::Aabb& kBox = testing::kWavyStock;

void expectSameRows(const ThreeMap& a, const ThreeMap& b) {
  for (int iv = 0; iv < a.columnsV(); ++iv)
    for (int iu = 0; iu < a.columnsU(); ++iu)
      ASSERT_EQ(a.height(iu, iv), b.height(iu, iv)) << "column " << iu << "," << iv;
  for (int family = 0; family < 2; ++family)
    for (int r = 0; r < a.rowCount(family); ++r)
      ASSERT_EQ(a.row(family, r), b.row(family, r)) << "family " << family << " row " << r;
}

StockOptions options(bool lazy, int brickZ = -1) {
  StockOptions o = testing::wavyOptions();
  o.step_volumes = false;  // lazy crossings need it off (as mdhd check runs)
  o.lazy_crossings = lazy;
  o.brick_z = brickZ;
  return o;
}

// What a test does between batches, to the lazy and the eager stock alike.
enum class Between { kNothing, kQueryLines, kSingleSteps };

// The zigzag in batches of `batch` steps, each cut through the shared-solid cutIfFast
// (lazy when the stock's options say so), refused ones step by step; with kSingleSteps
// every third batch is cut step by step (Stock::cut settles the cells it reaches),
// with kQueryLines an x line through the last pose is read after every batch.
void cutRows(Stock& stock, const geom::ToolPart& part, const std::vector<geom::ToolPose>& poses,
             std::size_t batch, Between between) {
  const auto step = [&](std::size_t i) {
    const auto s = geom::SweptVolume::between(part, poses[i - 1], poses[i], 0, 0.01);
    const auto fresh = geom::freshRegion(part, poses[i - 1], poses[i]);
    stock.cut(s, poses[i].axis, i > 1 && fresh ? &*fresh : nullptr);
  };
  step(1);
  std::vector<geom::Interval> line;
  int n = 0;
  for (std::size_t first = 2; first < poses.size(); first += batch, ++n) {
    const std::size_t last = std::min(poses.size() - 1, first + batch - 1);
    if (between == Between::kSingleSteps && n % 3 == 2) {
      for (std::size_t i = first; i <= last; ++i) step(i);
      continue;
    }
    geom::FreshRegion fresh;
    for (std::size_t i = first; i <= last; ++i) {
      const geom::FreshRegion one = geom::freshRegion(part, poses[i - 1], poses[i]).value();
      fresh.pieces.insert(fresh.pieces.end(), one.pieces.begin(), one.pieces.end());
    }
    auto chain = std::make_shared<const geom::SweptVolume>(geom::SweptVolume::chainOfTranslations(
        part, std::span(poses).subspan(first - 1, last - first + 2)));
    if (!stock.cutIfFast(std::shared_ptr<const geom::LineSolid>(chain), poses[first].axis, &fresh,
                         last - first + 1))
      for (std::size_t i = first; i <= last; ++i) step(i);
    if (between == Between::kQueryLines) {
      const GridSpec& g = stock.grid();
      const int iy = static_cast<int>(std::lround(g.toGrid(1, poses[last].tip.y)));
      const int iz = static_cast<int>(std::lround(g.toGrid(2, poses[last].tip.z)));
      stock.solidIntervals(0, iy, std::clamp(iz, 0, g.cubes[2]), line);
    }
  }
}

void expectSameStock(const Stock& lazy, const Stock& eager) {
  EXPECT_EQ(testing::differences(testing::allIntervals(lazy), testing::allIntervals(eager)), 0);
  EXPECT_EQ(lazy.volume(), eager.volume());
  const Stats a = lazy.stats(), b = eager.stats();
  EXPECT_EQ(a.leaves, b.leaves);
  EXPECT_EQ(a.embeddedSamples, b.embeddedSamples);
  EXPECT_EQ(a.directions, b.directions);
  EXPECT_EQ(a.overhangEvents, b.overhangEvents);
  lazy.checkInvariants();
}

// One map cut lazily and eagerly by the same random upright cuts (the ring fills and
// drops its oldest cut again and again), settled now and then, with the generations
// started just below where they are reset (their tags must not wrap): the same map.
TEST(LazyCrossingsMap, EqualsTheEagerMapThroughEvictionsAndAGenerationReset) {
  GridSpec grid;
  grid.h = 0.1;
  grid.cubes = {24, 20, 22};
  const GridBox box{{0, 0, 0}, {24, 20, 22}};
  ThreeMap eager(box, Direction{2, 1}, true), lazy(box, Direction{2, 1}, true);
  PendingCuts pending;
  pending.generation = 0xffff0000u - 7;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int cuts = 0;
  for (int step = 0; step < 80; ++step) {
    const glm::dvec3 tip{2.4 * unit(rng), 2.0 * unit(rng), 2.2 - 0.9 * unit(rng)};
    const glm::dvec3 axis = glm::normalize(glm::dvec3(0.05 * unit(rng), 0.0, 1.0));
    const double r = 0.2 + 0.4 * unit(rng);
    const std::shared_ptr<const geom::LineSolid> tool = unit(rng) < 0.6
                                                            ? testing::ballMill(tip, axis, r, 6.0)
                                                            : testing::flatMill(tip, axis, r, 6.0);
    const IntervalCache cache(grid, *tool);
    const FastCut e = fastCut(eager, cache, cache.touched(), nullptr);
    const FastCut l = fastCutLazy(lazy, cache, cache.touched(), tool, pending);
    ASSERT_EQ(e == FastCut::kOverhang, l == FastCut::kOverhang) << "step " << step;
    cuts += e != FastCut::kOverhang;
    if (step % 25 == 24) {
      settleCrossings(lazy, pending, grid);
      ASSERT_NO_FATAL_FAILURE(expectSameRows(lazy, eager)) << "step " << step;
      pending.generation = 0xffff0000u - 2;  // and once more across the reset
    }
  }
  EXPECT_GT(cuts, 40);
  settleCrossings(lazy, pending, grid);
  expectSameRows(lazy, eager);
  EXPECT_EQ(lazy.volume(), eager.volume());
}

struct LazyCase {
  geom::ToolShape shape;
  glm::dvec3 axis;
  std::size_t batch;
  int brickZ;
  Between between;
};

void PrintTo(const LazyCase& c, std::ostream* os) {
  *os << "shape " << static_cast<int>(c.shape) << ", axis (" << c.axis.x << ", " << c.axis.y << ", "
      << c.axis.z << "), batch " << c.batch << ", brick_z " << c.brickZ << ", between "
      << static_cast<int>(c.between);
}

class LazyCrossings : public ::testing::TestWithParam<LazyCase> {};

TEST_P(LazyCrossings, LeaveTheEagerStockToTheBit) {
  const LazyCase& c = GetParam();
  const geom::ToolPart part = testing::cutterPart(c.shape, 3.0);
  const auto poses = testing::wavyRows(glm::normalize(c.axis), 40, 0.25);
  Stock lazy(kBox, options(true, c.brickZ)), eager(kBox, options(false, c.brickZ));
  cutRows(lazy, part, poses, c.batch, c.between);
  cutRows(eager, part, poses, c.batch, c.between);
  EXPECT_LT(eager.volume(), 0.97 * 12 * 12 * 8);  // it cut something
  expectSameStock(lazy, eager);
}

INSTANTIATE_TEST_SUITE_P(
    ShapesBricksQueries, LazyCrossings,
    ::testing::Values(LazyCase{geom::ToolShape::kBall, {0, 0, 1}, 16, -1, Between::kNothing},
                      LazyCase{geom::ToolShape::kBall, {0, 0, 1}, 16, 0, Between::kNothing},
                      LazyCase{geom::ToolShape::kBall, {0, 0, 1}, 4, 0, Between::kQueryLines},
                      LazyCase{geom::ToolShape::kFlat, {0, 0, 1}, 16, 0, Between::kSingleSteps},
                      LazyCase{geom::ToolShape::kBull, {0, 0, 1}, 7, -1, Between::kSingleSteps},
                      LazyCase{geom::ToolShape::kDrill, {0, 0, 1}, 16, -1, Between::kQueryLines},
                      LazyCase{geom::ToolShape::kBall, {0.3, -0.2, 1}, 16, -1, Between::kNothing},
                      LazyCase{geom::ToolShape::kFlat, {-0.4, 0.1, 1}, 5, 0, Between::kSingleSteps},
                      LazyCase{geom::ToolShape::kBull, {1, 0, 0.3}, 16, -1, Between::kNothing}),
    [](const auto& p) { return "case" + std::to_string(p.index); });

// Random 5-axis moves from every side (overhangs, splits, side maps) cut eagerly
// between lazy batches: the slow path and the side maps settle what they reach.
TEST(LazyCrossingsMixed, RandomMovesBetweenBatchesLeaveTheEagerStock) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const auto poses = testing::wavyRows({0, 0, 1}, 40, 0.25);
  Stock lazy(kBox, options(true)), eager(kBox, options(false));
  testing::RandomToolMoves movesA(7, kBox), movesB(7, kBox);
  for (Stock* s : {&lazy, &eager}) {
    testing::RandomToolMoves& moves = s == &lazy ? movesA : movesB;
    for (int half = 0; half < 2; ++half) {
      const std::size_t from = half * poses.size() / 2, to = (half + 1) * poses.size() / 2;
      cutRows(*s, ball, std::vector(poses.begin() + from, poses.begin() + to), 8,
              Between::kNothing);
      for (int i = 0; i < 6; ++i) {
        const testing::ToolMove m = moves.next();
        s->cut(m.sweep, m.direction);
      }
    }
  }
  expectSameStock(lazy, eager);
}

// Single turning steps (a 5-axis raster: the axis leans a little more at every step)
// cut with the solid shared, each from where the last one left the tool held (fresh
// regions, as mdhd check cuts them), random moves from every side in between (side
// maps, overhangs, splits), a step now and then cut twice and a line read now and
// then: the z maps keep the steps' crossings pending, the stock is the eager one to
// the bit, and so is every step's CutResult::removed.
TEST(LazyCrossingsMixed, SingleTurningStepsLeaveTheEagerStock) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  auto poses = testing::wavyRows({0, 0, 1}, 40, 0.25);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const double lean = 0.35 * std::sin(0.05 * static_cast<double>(i));
    poses[i].axis = glm::normalize(glm::dvec3(lean, 0.5 * lean, 1.0));
  }
  Stock lazy(kBox, options(true)), eager(kBox, options(false));
  testing::RandomToolMoves movesA(3, kBox), movesB(3, kBox);
  std::int64_t touched[2] = {0, 0};
  std::vector<bool> removed[2];
  std::vector<geom::Interval> line;
  for (Stock* s : {&lazy, &eager}) {
    const int k = s == &lazy ? 0 : 1;
    testing::RandomToolMoves& moves = k == 0 ? movesA : movesB;
    std::optional<geom::ToolPose> held;
    for (std::size_t i = 1; i < poses.size(); ++i) {
      auto sweep = std::make_shared<const geom::SweptVolume>(
          geom::SweptVolume::between(ball, poses[i - 1], poses[i], 0, 0.01));
      std::optional<geom::FreshRegion> fresh;
      if (held) fresh = geom::freshRegion(ball, *held, sweep->translations());
      const glm::dvec3 dir = glm::normalize(poses[i - 1].axis + poses[i].axis);
      const CutResult r =
          s->cut(std::shared_ptr<const geom::LineSolid>(sweep), dir, fresh ? &*fresh : nullptr);
      touched[k] += r.touched;
      removed[k].push_back(r.removed);
      if (i % 5 == 0)  // the same step again: it reaches the maps and removes nothing
        removed[k].push_back(s->cut(std::shared_ptr<const geom::LineSolid>(sweep), dir).removed);
      const geom::Translation& last = sweep->translations().back();
      held = geom::ToolPose{last.to, last.axis};
      if (i % 50 == 0) {
        for (int m = 0; m < 3; ++m) {
          const testing::ToolMove move = moves.next();
          s->cut(move.sweep, move.direction);
        }
        held.reset();  // the tool left the raster
      }
      if (i % 17 == 0) {
        const GridSpec& g = s->grid();
        const int iy = static_cast<int>(std::lround(g.toGrid(1, poses[i].tip.y)));
        const int iz = static_cast<int>(std::lround(g.toGrid(2, poses[i].tip.z)));
        s->solidIntervals(0, iy, std::clamp(iz, 0, g.cubes[2]), line);
      }
    }
  }
  EXPECT_LT(eager.volume(), 0.97 * 12 * 12 * 8);
  EXPECT_GT(touched[1], 100);
  EXPECT_GE(touched[0], touched[1]);  // a lazy cut is touched wherever it reaches a z map
  // Whether a step surely removed material is the same answer either way.
  EXPECT_EQ(removed[0], removed[1]);
  EXPECT_GT(std::count(removed[1].begin(), removed[1].end(), true), 100);
  EXPECT_GT(std::count(removed[1].begin(), removed[1].end(), false), 20);
  const Stats st = eager.stats();
  EXPECT_GT(st.overhangEvents, 0);
  EXPECT_GT(st.directions[4], 0);  // +z maps (where the crossings wait) and side maps
  EXPECT_GT(st.directions[0] + st.directions[1] + st.directions[2] + st.directions[3], 0);
  expectSameStock(lazy, eager);
}

// A batch the fast path refuses leaves the pending crossings as they were; the cut
// made instead (with an overhang) settles the cells it reaches.
TEST(LazyCrossingsMixed, ARefusedBatchKeepsWhatWasPending) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const geom::ToolPart drill = testing::cutterPart(geom::ToolShape::kDrill, 1.0);
  const auto poses = testing::wavyRows({0, 0, 1}, 40, 0.25);
  const std::vector<geom::ToolPose> side{{{-1.0, 6.0, 3.65}, {-1, 0, 0}},
                                         {{4.0, 6.0, 3.65}, {-1, 0, 0}}};
  Stock lazy(kBox, options(true)), eager(kBox, options(false));
  for (Stock* s : {&lazy, &eager}) {
    cutRows(*s, ball, poses, 16, Between::kNothing);
    auto sweep = std::make_shared<const geom::SweptVolume>(
        geom::SweptVolume::chainOfTranslations(drill, side));
    EXPECT_FALSE(s->cutIfFast(std::shared_ptr<const geom::LineSolid>(sweep), {-1, 0, 0}, nullptr, 1)
                     .has_value());
    EXPECT_GT(s->cut(*sweep, {-1, 0, 0}).overhang_events, 0);
  }
  expectSameStock(lazy, eager);
}

// A vertical tool buried deeper than its flutes would leave material above them in a
// z map: the lazy batch is refused when planned, before any brick changes (no undo
// copies), exactly as the eager batch is refused after its undo.
TEST(LazyCrossingsMixed, ABatchRefusedWhenPlannedChangesNothing) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const geom::ToolPart small = testing::cutterPart(geom::ToolShape::kFlat, 1.0);  // 4 mm flutes
  const auto poses = testing::wavyRows({0, 0, 1}, 40, 0.25);
  const std::vector<geom::ToolPose> deep{{{6.0, 6.3, 1.0}, {0, 0, 1}},
                                         {{7.0, 6.3, 1.0}, {0, 0, 1}}};
  Stock lazy(kBox, options(true)), eager(kBox, options(false));
  const auto sweep = std::make_shared<const geom::SweptVolume>(
      geom::SweptVolume::chainOfTranslations(small, deep));
  for (Stock* s : {&lazy, &eager}) {
    cutRows(*s, ball, poses, 16, Between::kNothing);
    const std::uint64_t steps = s->steps();
    EXPECT_FALSE(
        s->cutIfFast(std::shared_ptr<const geom::LineSolid>(sweep), {0, 0, 1}, nullptr, 1));
    EXPECT_EQ(s->steps(), steps);
  }
  EXPECT_EQ(testing::differences(testing::allIntervals(lazy), testing::allIntervals(eager)), 0);
  for (Stock* s : {&lazy, &eager}) EXPECT_GT(s->cut(*sweep, {0, 0, 1}).overhang_events, 0);
  expectSameStock(lazy, eager);
}

// A clone holds the same pending cuts; each settles its own.
TEST(LazyCrossingsMixed, AClonedStockSettlesLikeItsOriginal) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const auto poses = testing::wavyRows({0, 0, 1}, 40, 0.25);
  Stock lazy(kBox, options(true, 0)), eager(kBox, options(false, 0));
  const std::size_t half = poses.size() / 2;
  cutRows(lazy, ball, std::vector(poses.begin(), poses.begin() + half), 16, Between::kNothing);
  const std::unique_ptr<Stock> copy = lazy.clone();
  cutRows(*copy, ball, std::vector(poses.begin() + half - 1, poses.end()), 16, Between::kNothing);
  cutRows(eager, ball, std::vector(poses.begin(), poses.begin() + half), 16, Between::kNothing);
  const auto halfway = testing::allIntervals(eager);
  EXPECT_EQ(testing::differences(testing::allIntervals(lazy), halfway), 0);  // the original
  cutRows(eager, ball, std::vector(poses.begin() + half - 1, poses.end()), 16, Between::kNothing);
  expectSameStock(*copy, eager);
}

// Queries from several threads at once (the overhang area reads lines on the stock's
// threads) settle once, and all read the settled stock.
TEST(LazyCrossingsMixed, QueriesFromTwoThreadsReadTheSettledStock) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const auto poses = testing::wavyRows({0, 0, 1}, 40, 0.25);
  Stock lazy(kBox, options(true, 0)), eager(kBox, options(false, 0));
  cutRows(lazy, ball, poses, 16, Between::kNothing);
  cutRows(eager, ball, poses, 16, Between::kNothing);
  const GridSpec& g = lazy.grid();
  std::vector<std::vector<double>> read(2);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t)
    threads.emplace_back([&, t] {
      std::vector<geom::Interval> line;
      for (int iz = 0; iz <= g.cubes[2]; ++iz)
        for (int iy = t; iy <= g.cubes[1]; iy += 2) {
          lazy.solidIntervals(0, iy, iz, line);
          for (const geom::Interval& i : line) read[t].insert(read[t].end(), {i.lo, i.hi});
        }
    });
  for (std::thread& t : threads) t.join();
  std::vector<double> expected[2];
  std::vector<geom::Interval> line;
  for (int t = 0; t < 2; ++t)
    for (int iz = 0; iz <= g.cubes[2]; ++iz)
      for (int iy = t; iy <= g.cubes[1]; iy += 2) {
        eager.solidIntervals(0, iy, iz, line);
        for (const geom::Interval& i : line) expected[t].insert(expected[t].end(), {i.lo, i.hi});
      }
  EXPECT_EQ(read[0], expected[0]);
  EXPECT_EQ(read[1], expected[1]);
}

// The lazy path is taken only where it may be: per-step volumes need every crossing.
TEST(LazyCrossingsMixed, StepVolumesKeepTheCutsEager) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const auto poses = testing::wavyRows({0, 0, 1}, 40, 0.25);
  StockOptions withVolumes = options(true);
  withVolumes.step_volumes = true;
  Stock a(kBox, withVolumes), b(kBox, options(false));
  const auto chain = std::make_shared<const geom::SweptVolume>(
      geom::SweptVolume::chainOfTranslations(ball, std::span(poses).first(12)));
  const auto r = a.cutIfFast(std::shared_ptr<const geom::LineSolid>(chain), {0, 0, 1}, nullptr, 11);
  ASSERT_TRUE(r.has_value());
  EXPECT_GT(r->removed_volume, 0.0);  // computed, so the crossings were
  b.cutIfFast(*chain, {0, 0, 1}, nullptr, 11);
  EXPECT_NEAR(r->removed_volume, 12.0 * 12 * 8 - b.volume(), 1e-9 * b.volume());
}

}  // namespace
}  // namespace mdhd::mdh

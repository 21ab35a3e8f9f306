// A chain of translations cut as batches (Stock::cutIfFast on the union of a few
// steps' sweeps, the union of their fresh regions) leaves the stock the steps cut one
// by one leave: the same cells, directions and splits, and the same grid-line
// intervals but for a few crossings, each within a grid spacing (an edge that two
// steps cut from both ends keeps one crossing per level: the union's and the
// sequence's can differ inside the edge) and a few rounding ulps. A batch that
// would need the slow path is refused with the stock untouched, to the bit, and
// cut step by step.
#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_fresh_region.h"
#include "sim/mdh/stock.h"
#include "tests/mdh/random_tool_moves.h"
#include "tests/mdh/stock_lines.h"
#include "tests/mdh/wavy_rows.h"

namespace mdhd::mdh {
namespace {

const geom::Aabb& kBox = testing::kWavyStock;

std::vector<geom::ToolPose> rows(const glm::dvec3& axis) {
  return testing::wavyRows(axis, 40, 0.25);
}

struct Outcome {
  std::int64_t refused = 0;  // batches the fast path would not take
  std::int64_t events = 0;   // overhang events of the cuts made
};

// Steps one by one when batch == 1, else batches of up to `batch` steps after the
// first (which has no earlier pose to take a fresh region from).
Outcome cutChain(Stock& stock, const geom::ToolPart& part, const std::vector<geom::ToolPose>& poses,
                 std::size_t batch) {
  Outcome out;
  const auto step = [&](std::size_t i) {
    const auto s = geom::SweptVolume::between(part, poses[i - 1], poses[i], 0, 0.01);
    if (i == 1) {
      out.events += stock.cut(s, poses[i].axis).overhang_events;
      return;
    }
    const geom::FreshRegion fresh = geom::freshRegion(part, poses[i - 1], poses[i]).value();
    out.events += stock.cut(s, poses[i].axis, &fresh).overhang_events;
  };
  step(1);
  for (std::size_t first = 2; first < poses.size(); first += batch) {
    const std::size_t last = std::min(poses.size() - 1, first + batch - 1);
    if (batch == 1) {
      step(first);
      continue;
    }
    geom::FreshRegion fresh;
    for (std::size_t i = first; i <= last; ++i) {
      const geom::FreshRegion one = geom::freshRegion(part, poses[i - 1], poses[i]).value();
      fresh.pieces.insert(fresh.pieces.end(), one.pieces.begin(), one.pieces.end());
    }
    const auto chain = geom::SweptVolume::chainOfTranslations(
        part, std::span(poses).subspan(first - 1, last - first + 2));
    const std::uint64_t before = stock.steps();
    if (const auto r = stock.cutIfFast(chain, poses[first].axis, &fresh, last - first + 1)) {
      EXPECT_EQ(r->overhang_events, 0);
      EXPECT_EQ(stock.steps(), before + (last - first + 1));
      continue;
    }
    ++out.refused;
    EXPECT_EQ(stock.steps(), before);
    for (std::size_t i = first; i <= last; ++i) step(i);
  }
  return out;
}

struct BatchCase {
  geom::ToolShape shape;
  glm::dvec3 axis;
  std::size_t batch;
};

class BatchedCuts : public ::testing::TestWithParam<BatchCase> {};

TEST_P(BatchedCuts, LeaveExactlyTheStockOfSingleSteps) {
  const geom::ToolPart part = testing::cutterPart(GetParam().shape, 3.0);
  const auto poses = rows(glm::normalize(GetParam().axis));
  Stock single(kBox, testing::wavyOptions()), batched(kBox, testing::wavyOptions());
  const Outcome one = cutChain(single, part, poses, 1);
  const Outcome many = cutChain(batched, part, poses, GetParam().batch);
  EXPECT_LT(single.volume(), 0.97 * 12 * 12 * 8);  // it cut something
  EXPECT_NEAR(batched.volume(), single.volume(), 1e-6 * single.volume());
  const auto lines = testing::allIntervals(batched), reference = testing::allIntervals(single);
  ASSERT_EQ(lines.size(), reference.size());
  EXPECT_EQ(testing::differences(lines, reference, batched.grid().h), 0);
  EXPECT_LE(testing::differences(lines, reference, 1e-9), 2);
  const Stats a = batched.stats(), b = single.stats();
  EXPECT_EQ(a.leaves, b.leaves);
  EXPECT_EQ(a.splitsDirect + a.splitsIndirect + a.splitsSignConflict + a.splitsFallback,
            b.splitsDirect + b.splitsIndirect + b.splitsSignConflict + b.splitsFallback);
  EXPECT_EQ(a.overhangEvents, b.overhangEvents);
  EXPECT_EQ(a.embeddedSamples, b.embeddedSamples);
  EXPECT_EQ(a.directions, b.directions);
  EXPECT_EQ(many.events, one.events);
  EXPECT_EQ(batched.steps(), single.steps());
  batched.checkInvariants();
}

INSTANTIATE_TEST_SUITE_P(ShapesAxesSizes, BatchedCuts,
                         ::testing::Values(BatchCase{geom::ToolShape::kBall, {0, 0, 1}, 4},
                                           BatchCase{geom::ToolShape::kBall, {0, 0, 1}, 16},
                                           BatchCase{geom::ToolShape::kFlat, {0, 0, 1}, 16},
                                           BatchCase{geom::ToolShape::kBull, {0, 0, 1}, 7},
                                           BatchCase{geom::ToolShape::kDrill, {0, 0, 1}, 16},
                                           BatchCase{geom::ToolShape::kBall, {0.3, -0.2, 1}, 16},
                                           BatchCase{geom::ToolShape::kFlat, {-0.4, 0.1, 1}, 5},
                                           BatchCase{geom::ToolShape::kBull, {1, 0, 0.3}, 16}),
                         [](const auto& p) { return "case" + std::to_string(p.index); });

// A side drilling under a floor cut from above, inside the floor's +z cells, needs
// new directions or splits: the
// batch is refused and the stock is left as it was, to the bit.
TEST(BatchedCutsRefusal, LeavesTheStockUntouched) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const auto poses = rows({0, 0, 1});
  Stock stock(kBox, testing::wavyOptions());
  cutChain(stock, ball, poses, 1);
  const auto before = testing::allIntervals(stock);
  const Stats statsBefore = stock.stats();
  const std::uint64_t steps = stock.steps();

  const geom::ToolPart drill = testing::cutterPart(geom::ToolShape::kDrill, 1.0);
  const std::vector<geom::ToolPose> side{{{-1.0, 6.0, 3.65}, {-1, 0, 0}},
                                         {{4.0, 6.0, 3.65}, {-1, 0, 0}}};
  const auto sweep = geom::SweptVolume::chainOfTranslations(drill, side);
  EXPECT_FALSE(stock.cutIfFast(sweep, {-1, 0, 0}, nullptr, 1).has_value());
  EXPECT_EQ(testing::differences(testing::allIntervals(stock), before), 0);
  EXPECT_EQ(stock.stats().leaves, statsBefore.leaves);
  EXPECT_EQ(stock.steps(), steps);
  // The ordinary cut takes it, with an overhang.
  EXPECT_GT(stock.cut(sweep, {-1, 0, 0}).overhang_events, 0);
  stock.checkInvariants();
}

TEST(ChainOfTranslations, RefusesATurningAxis) {
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const std::vector<geom::ToolPose> turn{{{1, 1, 5}, {0, 0, 1}}, {{2, 1, 5}, {0, 0.1, 1}}};
  EXPECT_THROW(geom::SweptVolume::chainOfTranslations(ball, turn), std::invalid_argument);
  EXPECT_THROW(geom::SweptVolume::chainOfTranslations(ball, std::span(turn).first(1)),
               std::invalid_argument);
}

}  // namespace
}  // namespace mdhd::mdh

// Cutting a chain of translations with each step's fresh region (Stock::cut skips
// what the previous step's end pose removed) leaves exactly the stock a full cut
// leaves: same volume and intervals on every grid line, to the bit.
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

using testing::kWavyStock;

std::vector<geom::ToolPose> zigzag(const glm::dvec3& axis) {
  return testing::wavyRows(axis, 24, 0.4);
}

// Wrong on purpose: the region of the move backwards (its trailing half).
enum class Region { kNone, kFresh, kBackwards };

void cutChain(Stock& stock, const geom::ToolPart& part, const std::vector<geom::ToolPose>& poses,
              Region use) {
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const geom::ToolPose &a = poses[i - 1], &b = poses[i];
    const auto s = geom::SweptVolume::between(part, a, b, 0, 0.01);
    std::optional<geom::FreshRegion> fresh;
    if (i > 1 && use == Region::kFresh) fresh = geom::freshRegion(part, a, b);
    if (i > 1 && use == Region::kBackwards) fresh = geom::freshRegion(part, b, a);
    stock.cut(s, a.axis, fresh ? &*fresh : nullptr);
  }
}

struct FreshCase {
  geom::ToolShape shape;
  glm::dvec3 axis;
};

class FreshCuts : public ::testing::TestWithParam<FreshCase> {};

TEST_P(FreshCuts, LeaveExactlyTheStockOfFullCuts) {
  const geom::ToolPart part = testing::cutterPart(GetParam().shape, 3.0);
  const auto poses = zigzag(glm::normalize(GetParam().axis));
  Stock full(kWavyStock, testing::wavyOptions()), fresh(kWavyStock, testing::wavyOptions());
  cutChain(full, part, poses, Region::kNone);
  cutChain(fresh, part, poses, Region::kFresh);
  EXPECT_LT(full.volume(), 0.97 * 12 * 12 * 8);  // it cut something
  EXPECT_EQ(fresh.volume(), full.volume());
  // Same intervals on every line, to the bit (kToolSlack keeps a full cut from
  // moving trailing-side crossings by rounding).
  EXPECT_EQ(testing::differences(testing::allIntervals(fresh), testing::allIntervals(full)), 0);
  EXPECT_EQ(fresh.stats().leaves, full.stats().leaves);
  fresh.checkInvariants();
}

INSTANTIATE_TEST_SUITE_P(ShapesAndAxes, FreshCuts,
                         ::testing::Values(FreshCase{geom::ToolShape::kBall, {0, 0, 1}},
                                           FreshCase{geom::ToolShape::kFlat, {0, 0, 1}},
                                           FreshCase{geom::ToolShape::kBull, {0, 0, 1}},
                                           FreshCase{geom::ToolShape::kDrill, {0, 0, 1}},
                                           FreshCase{geom::ToolShape::kBall, {0.3, -0.2, 1}},
                                           FreshCase{geom::ToolShape::kFlat, {-0.4, 0.1, 1}}),
                         [](const auto& p) { return "case" + std::to_string(p.index); });

// The comparison above can fail: skipping the leading half instead loses cuts.
TEST(FreshCutsCheck, AWrongRegionLeavesADifferentStock) {
  const geom::ToolPart part = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  const auto poses = zigzag({0, 0, 1});
  Stock full(kWavyStock, testing::wavyOptions()), wrong(kWavyStock, testing::wavyOptions());
  cutChain(full, part, poses, Region::kNone);
  cutChain(wrong, part, poses, Region::kBackwards);
  EXPECT_GT(wrong.volume(), full.volume() + 1.0);
}

// A 5-axis chain (the zigzag with a turning axis), each step swept as the check sweeps
// it (midpoint axes) and cut with the region from where the previous step left the
// part held.
std::vector<geom::ToolPose> turningZigzag() {
  return testing::turningRows(24, 0.4);
}

double cutTurningChain(Stock& stock, const geom::ToolPart& part, bool useRegion, bool reverse) {
  const auto poses = turningZigzag();
  std::optional<geom::ToolPose> held;
  int withRegion = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const geom::ToolPose &a = poses[i - 1], &b = poses[i];
    const auto s = geom::SweptVolume::between(part, a, b, 0, 0.01, geom::SweepEnds::kMidpoints);
    std::optional<geom::FreshRegion> fresh;
    if (useRegion && held) {
      if (reverse) {  // wrong on purpose: the turns backwards, each translation's region reversed
        std::vector<geom::Translation> back;
        for (const geom::Translation& t : s.translations()) back.push_back({t.to, t.from, t.axis});
        fresh = geom::freshRegion(part, *held, back);
        if (!fresh) fresh = geom::FreshRegion{};
      } else {
        fresh = geom::freshRegion(part, *held, s.translations());
      }
    }
    if (fresh) ++withRegion;
    stock.cut(s, a.axis, fresh ? &*fresh : nullptr);
    held = geom::ToolPose{s.translations().back().to, s.translations().back().axis};
  }
  return withRegion;
}

TEST(FreshCutsTurning, LeaveExactlyTheStockOfFullCuts) {
  for (geom::ToolShape shape : {geom::ToolShape::kBall, geom::ToolShape::kBull}) {
    const geom::ToolPart part = testing::cutterPart(shape, 3.0);
    Stock full(kWavyStock, testing::wavyOptions()), fresh(kWavyStock, testing::wavyOptions());
    cutTurningChain(full, part, false, false);
    // Every step but the first has a region: the held poses share the pivot.
    EXPECT_EQ(cutTurningChain(fresh, part, true, false), int(turningZigzag().size()) - 2);
    EXPECT_LT(full.volume(), 0.97 * 12 * 12 * 8);
    EXPECT_EQ(fresh.volume(), full.volume());
    EXPECT_EQ(testing::differences(testing::allIntervals(fresh), testing::allIntervals(full)), 0);
    EXPECT_EQ(fresh.stats().leaves, full.stats().leaves);
    fresh.checkInvariants();
  }
}

TEST(FreshCutsTurning, AWrongRegionLeavesADifferentStock) {
  const geom::ToolPart part = testing::cutterPart(geom::ToolShape::kBall, 3.0);
  Stock full(kWavyStock, testing::wavyOptions()), wrong(kWavyStock, testing::wavyOptions());
  cutTurningChain(full, part, false, false);
  cutTurningChain(wrong, part, true, true);
  EXPECT_GT(wrong.volume(), full.volume() + 1.0);
}

}  // namespace
}  // namespace mdhd::mdh

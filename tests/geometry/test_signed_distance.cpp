// Signed distances to tool parts: exact values on the axis, the rims and the corners.
#include "sim/geometry/signed_distance.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::makeTool;

TEST(SignedDistance, FlatEndMill) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kFlat), ToolPartKind::kCutter);  // R3 F12
  const ToolPose up{{0, 0, 0}, {0, 0, 1}};
  EXPECT_DOUBLE_EQ(signedDistance(part, up, {0, 0, -2}), 2.0);    // below the tip
  EXPECT_DOUBLE_EQ(signedDistance(part, up, {0, 0, 1}), -1.0);    // just inside the bottom
  EXPECT_DOUBLE_EQ(signedDistance(part, up, {2.5, 0, 6}), -0.5);  // nearer the side
  EXPECT_DOUBLE_EQ(signedDistance(part, up, {0, 5, 6}), 2.0);
  EXPECT_DOUBLE_EQ(signedDistance(part, up, {0, 6, 16}), 5.0);  // off the top rim: 3-4-5
  EXPECT_DOUBLE_EQ(signedDistance(part, up, {3, 0, 12}), 0.0);
}

TEST(SignedDistance, BallAndDrillTips) {
  const ToolPart ball = makeToolPart(makeTool(ToolShape::kBall), ToolPartKind::kCutter);
  const glm::dvec3 w = glm::normalize(glm::dvec3(1, 1, 1));
  const ToolPose pose{{1, 2, 3}, w};
  // Along any direction from the ball's centre (tip + R w) below its equator.
  const glm::dvec3 centre = pose.tip + 3.0 * w;
  const glm::dvec3 down = glm::normalize(glm::dvec3(-1, -0.2, -0.5));
  EXPECT_NEAR(signedDistance(ball, pose, centre + 5.0 * down), 2.0, 1e-12);
  EXPECT_NEAR(signedDistance(ball, pose, centre + 1.0 * down), -2.0, 1e-12);
  EXPECT_NEAR(signedDistance(ball, pose, centre), -3.0, 1e-12);
  // Drill 90 degrees: the cone's side is at 45 degrees; a point on the axis below the
  // apex is that far from it, one above it is inside by its height / sqrt 2.
  Tool d = makeTool(ToolShape::kDrill);
  d.tip_angle = 90.0;
  const ToolPart drill = makeToolPart(d, ToolPartKind::kCutter);
  const ToolPose up{{0, 0, 0}, {0, 0, 1}};
  EXPECT_NEAR(signedDistance(drill, up, {0, 0, -1.5}), 1.5, 1e-12);
  EXPECT_NEAR(signedDistance(drill, up, {0, 0, 1}), -std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(signedDistance(drill, up, {2, 0, 0}), std::sqrt(2.0), 1e-12);
}

TEST(SignedDistance, HolderIsTheNearestOfItsCylinders) {
  const ToolPart holder = makeToolPart(makeTool(ToolShape::kFlat), ToolPartKind::kHolder);
  const ToolPose up{{0, 0, 0}, {0, 0, 1}};  // r 10 on z 35..50, r 15 on z 25..35
  EXPECT_DOUBLE_EQ(signedDistance(holder, up, {12, 0, 40}), 2.0);
  EXPECT_DOUBLE_EQ(signedDistance(holder, up, {12, 0, 30}), -3.0);
  EXPECT_DOUBLE_EQ(signedDistance(holder, up, {0, 0, 20}), 5.0);
  const ToolPart none = makeToolPart(Tool{makeTool(ToolShape::kFlat)}, ToolPartKind::kCutter);
  EXPECT_LT(signedDistance(none, up, {0, 0, 5}), 0.0);
}

}  // namespace
}  // namespace mdhd::geom

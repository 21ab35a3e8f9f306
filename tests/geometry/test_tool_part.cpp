// The tool's parts standing at one pose: exact line intervals and closed-form volumes.
#include "sim/geometry/tool_part.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/signed_distance.h"
#include "sim/geometry/swept_volume.h"
#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::kPi;
using testing::makeTool;

const ToolPose kUp{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};

TEST(ToolPart, ZLinesThroughAnUprightBallEndAreExact) {
  const Tool tool = makeTool(ToolShape::kBall);  // R 3, flutes 12
  const SweptVolume s = SweptVolume::at(makeToolPart(tool, ToolPartKind::kCutter), kUp);
  std::vector<Interval> out;
  for (double x = -3.05; x <= 3.05; x += 0.1)
    for (double y = -3.05; y <= 3.05; y += 0.1) {
      out.clear();
      s.lineIntervals(2, x, y, out);
      const double rho2 = x * x + y * y;
      if (rho2 > 9.0) {
        EXPECT_TRUE(out.empty()) << x << " " << y;
        continue;
      }
      ASSERT_EQ(out.size(), 1u) << x << " " << y;
      EXPECT_NEAR(out[0].lo, 3.0 - std::sqrt(9.0 - rho2), 1e-12);
      EXPECT_NEAR(out[0].hi, 12.0, 1e-12);
    }
}

TEST(ToolPart, XLinesThroughAnUprightDrillAreExact) {
  const Tool tool = makeTool(ToolShape::kDrill);  // 118 degrees: cone height 3 / tan 59
  const double h = 3.0 / std::tan(59.0 * kPi / 180.0);
  const SweptVolume s = SweptVolume::at(makeToolPart(tool, ToolPartKind::kCutter), kUp);
  std::vector<Interval> out;
  for (double z = 0.05; z < 12.0; z += 0.1)
    for (double y = -2.95; y < 3.0; y += 0.1) {
      out.clear();
      s.lineIntervals(0, y, z, out);
      const double r = z < h ? 3.0 * z / h : 3.0;
      if (std::abs(y) >= r) {
        EXPECT_TRUE(out.empty());
        continue;
      }
      ASSERT_EQ(out.size(), 1u);
      EXPECT_NEAR(out[0].hi, std::sqrt(r * r - y * y), 1e-12);
      EXPECT_NEAR(out[0].lo, -std::sqrt(r * r - y * y), 1e-12);
    }
}

TEST(ToolPart, VolumesMatchClosedForms) {
  const double R = 3.0;
  const double F = 12.0;
  for (ToolShape shape : testing::allShapes()) {
    const Tool tool = makeTool(shape);
    const ToolPart part = makeToolPart(tool, ToolPartKind::kCutter);
    double exact = 0.0;
    switch (shape) {
      case ToolShape::kFlat:
        exact = kPi * R * R * F;
        break;
      case ToolShape::kBall:
        exact = 2.0 / 3.0 * kPi * R * R * R + kPi * R * R * (F - R);
        break;
      case ToolShape::kDrill: {
        const double h = tool.tipHeight();
        exact = kPi * R * R * h / 3.0 + kPi * R * R * (F - h);
        break;
      }
      case ToolShape::kBull: {
        // Pappus: core cylinder + the quarter disk of the corner turned about the axis.
        const double rc = tool.corner_radius;
        const double a = R - rc;
        exact = kPi * a * a * rc +
                2.0 * kPi * (kPi * rc * rc / 4.0) * (a + 4.0 * rc / (3.0 * kPi)) +
                kPi * R * R * (F - rc);
        // The corner's frustums lie inside, at most the tolerance below the torus.
        const double cornerArea = 2.0 * kPi * (kPi / 2.0 * rc) * (a + 2.0 * rc / kPi);
        const double approx = testing::partVolume(part);
        EXPECT_LT(approx, exact);
        EXPECT_GT(approx, exact - cornerArea * kDefaultCornerTolerance);
        break;
      }
    }
    if (shape != ToolShape::kBull) {
      EXPECT_NEAR(testing::partVolume(part), exact, 1e-9);
    }
    // Tilted and off the origin, integrated along each grid direction.
    const ToolPose pose{{0.3, -0.2, 0.1}, glm::normalize(glm::dvec3(0.3, -0.5, 0.8))};
    const SweptVolume s = SweptVolume::at(part, pose);
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_NEAR(testing::integrateVolume(s, axis, 0.03), exact, 2e-4 * exact)
          << toolShapeName(shape) << " axis " << axis;
  }
}

TEST(ToolPart, TiltedPartsAgreeWithTheSignedDistanceOnEveryLine) {
  const ToolPose pose{{1.0, 2.0, -1.0}, glm::normalize(glm::dvec3(-0.4, 0.2, 0.9))};
  for (ToolShape shape : testing::allShapes()) {
    const Tool tool = makeTool(shape);
    for (ToolPartKind kind : {ToolPartKind::kCutter, ToolPartKind::kShank, ToolPartKind::kHolder}) {
      const ToolPart part = makeToolPart(tool, kind);
      const SweptVolume s = SweptVolume::at(part, pose);
      const Aabb b = s.bounds();
      const testing::Sdf sd = [&](const glm::dvec3& p) { return signedDistance(part, pose, p); };
      int decided = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const int i1 = (axis + 1) % 3;
        const int i2 = (axis + 2) % 3;
        const double du = (b.hi[i1] - b.lo[i1]) / 13.0;
        const double dv = (b.hi[i2] - b.lo[i2]) / 13.0;
        for (double u = b.lo[i1] + du / 3; u < b.hi[i1]; u += du)
          for (double v = b.lo[i2] + dv / 3; v < b.hi[i2]; v += dv)
            decided += testing::checkLine(s, sd, axis, u, v, 1e-9, 1e-9, 0.05);
      }
      EXPECT_GT(decided, 5000) << toolShapeName(shape);
    }
  }
}

TEST(ToolPart, PartsStackUpTheTool) {
  Tool tool = makeTool(ToolShape::kBall);  // flutes 12, holder 15 + 10 below the gauge at 50
  const ToolPart shank = makeToolPart(tool, ToolPartKind::kShank);
  ASSERT_EQ(shank.bodies.size(), 1u);
  EXPECT_EQ(shank.bodies[0].bottom(), 12.0);
  EXPECT_EQ(shank.bodies[0].top(), 25.0);
  const ToolPart holder = makeToolPart(tool, ToolPartKind::kHolder);
  ASSERT_EQ(holder.bodies.size(), 2u);
  EXPECT_EQ(holder.bodies[0].bottom(), 35.0);  // first listed: at the gauge point
  EXPECT_EQ(holder.bodies[0].top(), 50.0);
  EXPECT_EQ(holder.bodies[0].radiusAt(40.0), 10.0);
  EXPECT_EQ(holder.bodies[1].bottom(), 25.0);
  EXPECT_EQ(holder.bodies[1].radiusAt(30.0), 15.0);
  EXPECT_NEAR(holder.reach(), std::hypot(10.0, 50.0), 1e-12);
  tool.holder.clear();
  EXPECT_TRUE(makeToolPart(tool, ToolPartKind::kHolder).empty());
  EXPECT_EQ(makeToolPart(tool, ToolPartKind::kShank).bodies[0].top(), 50.0);
}

TEST(ToolPart, BullCornerStaysWithinItsTolerance) {
  Tool tool = makeTool(ToolShape::kBull, 10.0, 20.0);
  tool.corner_radius = 2.0;
  for (double tol : {1e-2, 1e-3, 1e-4}) {
    const ConvexBody body = makeToolPart(tool, ToolPartKind::kCutter, tol).bodies[0];
    double worst = 0.0;
    for (double z = 0.0; z <= 2.0; z += 1e-4) {
      const double exact = 3.0 + std::sqrt(std::max(0.0, 4.0 - (2.0 - z) * (2.0 - z)));
      const double gap = exact - body.radiusAt(z);
      EXPECT_GE(gap, -1e-12);
      // Horizontal gap bounds the normal gap; near z = 0 the arc is flat, use the normal.
      worst = std::max(worst, std::abs(std::hypot(body.radiusAt(z) - 3.0, z - 2.0) - 2.0));
    }
    EXPECT_LE(worst, tol * (1 + 1e-9));
    EXPECT_GT(worst, tol / 4.0);  // and not needlessly fine
  }
}

TEST(ToolPart, InvalidToolsAreRefused) {
  Tool tool = makeTool(ToolShape::kBull);
  tool.corner_radius = 4.0;
  EXPECT_THROW(makeToolPart(tool, ToolPartKind::kCutter), std::invalid_argument);
}

TEST(ToolPart, SmoothJoinsAreTheBallsEquatorOnly) {
  // The ball's zone meets its cylinder with the same slope; the drill's cone and the
  // bull's frustums meet with a crease, where a section's extreme may lie.
  auto pieces = [](ToolShape shape) {
    return makeToolPart(makeTool(shape), ToolPartKind::kCutter).bodies[0].pieces;
  };
  const auto ball = pieces(ToolShape::kBall);
  ASSERT_EQ(ball.size(), 2u);
  EXPECT_TRUE(smoothJoin(ball[0], ball[1]));
  const auto drill = pieces(ToolShape::kDrill);
  ASSERT_EQ(drill.size(), 2u);
  EXPECT_FALSE(smoothJoin(drill[0], drill[1]));
  const auto bull = pieces(ToolShape::kBull);
  ASSERT_GT(bull.size(), 3u);
  for (std::size_t i = 0; i + 1 < bull.size(); ++i) EXPECT_FALSE(smoothJoin(bull[i], bull[i + 1]));
  // Pieces that do not touch, or meet at another radius, never join smoothly.
  EXPECT_FALSE(smoothJoin(cylinderPiece(0.0, 1.0, 2.0), cylinderPiece(1.5, 2.0, 2.0)));
  EXPECT_FALSE(smoothJoin(cylinderPiece(0.0, 1.0, 2.0), cylinderPiece(1.0, 2.0, 2.5)));
  EXPECT_TRUE(smoothJoin(cylinderPiece(0.0, 1.0, 2.0), cylinderPiece(1.0, 2.0, 2.0)));
}

}  // namespace
}  // namespace mdhd::geom

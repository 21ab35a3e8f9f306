// The tool's parts standing at one pose: exact line intervals and closed-form volumes.
#include "sim/geometry/tool_part.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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

// The support function h(n) = max p . n of the part (tip at the origin, axis +z),
// from points on every piece's surface and the rims.
double support(const std::vector<glm::dvec3>& pts, const glm::dvec3& n) {
  double h = -1e300;
  for (const glm::dvec3& p : pts) h = std::max(h, glm::dot(p, n));
  return h;
}

std::vector<glm::dvec3> surfacePoints(const ToolPart& part) {
  std::vector<glm::dvec3> pts;
  for (const ConvexBody& b : part.bodies)
    for (const RevolvedPiece& p : b.pieces)
      for (int i = 0; i <= 100; ++i) {
        const double z = p.z0 + (p.z1 - p.z0) * i / 100.0;
        const double r = p.radiusAt(z);
        for (int k = 0; k < 180; ++k)
          pts.push_back({r * std::cos(k * kPi / 90), r * std::sin(k * kPi / 90), z});
      }
  return pts;
}

// turnRate bounds how fast the support function changes as the part turns about the
// pivot (in any direction, any turn), and is not loose: the most measured on sampled
// surfaces over random directions and turns comes within 25 % of it.
TEST(ToolPart, TurnRateBoundsTheSurfacesSpeed) {
  std::mt19937 rng(3);
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape, 6.0, 15.0), ToolPartKind::kCutter);
    const std::vector<glm::dvec3> pts = surfacePoints(part);
    for (double pivot : {part.turnPivot(), 0.0, 15.0}) {
      const double rate = part.turnRate(pivot);
      EXPECT_LE(rate, part.reach(pivot) + 1e-12);
      const double angle = 1e-3;
      double most = 0.0;
      for (int trial = 0; trial < 400; ++trial) {
        const glm::dvec3 n = testing::randomUnit(rng);
        const glm::dvec3 k = testing::randomUnit(rng);
        // The part turned by `angle` about k through the pivot: h'(n) = h(R^T n) + c . n
        // with c the pivot's offset, so the change is in the direction R^T n.
        const glm::dvec3 c{0, 0, pivot};
        const glm::dvec3 back = std::cos(angle) * n - std::sin(angle) * glm::cross(k, n) +
                                (1 - std::cos(angle)) * glm::dot(k, n) * k;
        const double turned = support(pts, back) - glm::dot(c, back) + glm::dot(c, n);
        most = std::max(most, std::abs(turned - support(pts, n)) / angle);
      }
      EXPECT_LE(most, rate * (1 + 1e-2) + 1e-6) << toolShapeName(shape) << " pivot " << pivot;
      EXPECT_GE(most, 0.75 * rate) << toolShapeName(shape) << " pivot " << pivot;
    }
  }
}

// The pivot is the least rate over the part's height.
TEST(ToolPart, TurnPivotHasTheLeastRate) {
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape, 8.0, 25.0), ToolPartKind::kCutter);
    const double best = part.turnRate(part.turnPivot());
    for (double h = 0.0; h <= 25.0; h += 0.05) EXPECT_GE(part.turnRate(h), best - 1e-9) << h;
  }
  // A flat end mill of radius 4 and 25 mm: both rims alike at half height.
  const ToolPart flat = makeToolPart(makeTool(ToolShape::kFlat, 8.0, 25.0), ToolPartKind::kCutter);
  EXPECT_NEAR(flat.turnPivot(), 12.5, 1e-6);
  EXPECT_NEAR(flat.turnRate(12.5), std::hypot(4.0, 12.5), 1e-12);
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

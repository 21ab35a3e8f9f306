// Sweeps with a constant axis (every 3-axis move) are exact: against Cauchy's volume
// formula and a brute-force membership reference that minimises over the move.
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/signed_distance.h"
#include "sim/geometry/swept_volume.h"
#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::kPi;
using testing::makeTool;

// Signed distance to the part swept from a to b with a fixed axis, minimised over the
// move per convex body (each body's distance is convex along the move).
testing::Sdf sweptSdf(const ToolPart& part, const ToolPose& a, const glm::dvec3& to) {
  return [&part, a, to](const glm::dvec3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const ConvexBody& body : part.bodies) {
      ToolPart one;
      one.bodies = {body};
      best = std::min(best, testing::minimiseConvex([&](double s) {
                        const ToolPose at{a.tip + s * (to - a.tip), a.axis};
                        return signedDistance(one, at, p);
                      }));
    }
    return best;
  };
}

TEST(TranslationalSweep, FlatEndMillSidewaysSweepsCylinderPlusSlab) {
  const double R = 3.0;
  const double H = 12.0;
  const double L = 7.5;
  const ToolPart part = makeToolPart(makeTool(ToolShape::kFlat), ToolPartKind::kCutter);
  const SweptVolume s =
      SweptVolume::between(part, {{0, 0, 0}, {0, 0, 1}}, {{L, 0, 0}, {0, 0, 1}}, 0, 0.01);
  ASSERT_EQ(s.translations().size(), 1u);
  EXPECT_EQ(s.errorBound(), 0.0);
  const double exact = kPi * R * R * H + 2 * R * H * L;
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_NEAR(testing::integrateVolume(s, axis, 0.025), exact, 1e-4 * exact) << axis;
  // z lines: the full flute height wherever the line passes over the swept footprint.
  std::vector<Interval> out;
  s.lineIntervals(2, 5.0, 2.9, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].lo, 0.0);
  EXPECT_DOUBLE_EQ(out[0].hi, 12.0);
  out.clear();
  s.lineIntervals(0, 1.0, 6.0, out);  // x line at y 1, z 6: from the start disk to the end disk
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].lo, -std::sqrt(8.0), 1e-12);
  EXPECT_NEAR(out[0].hi, L + std::sqrt(8.0), 1e-12);
}

TEST(TranslationalSweep, BallAlongALineIsACapsuleAndItsStem) {
  // A ball end moved along its own axis' normal plane and obliquely: Cauchy's formula,
  // volume + L * area of the projection along the move.
  const double R = 3.0;
  const double F = 12.0;
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall), ToolPartKind::kCutter);
  const double vol = 2.0 / 3.0 * kPi * R * R * R + kPi * R * R * (F - R);
  const double L = 5.0;
  const glm::dvec3 w = glm::normalize(glm::dvec3(0.2, 0.3, 1.0));
  // Along the axis (a plunge): the projection is the disk.
  const SweptVolume plunge = SweptVolume::between(part, {{0, 0, 0}, w}, {-L * w, w}, 0, 0.01);
  EXPECT_NEAR(testing::integrateVolume(plunge, 2, 0.025), vol + L * kPi * R * R, 2e-4 * vol);
  // Perpendicular to the axis: the meridian section.
  const glm::dvec3 side = glm::normalize(glm::cross(w, glm::dvec3(1, 0, 0)));
  const SweptVolume sideways = SweptVolume::between(part, {{0, 0, 0}, w}, {L * side, w}, 0, 0.01);
  const double section = kPi * R * R / 2 + 2 * R * (F - R);
  EXPECT_NEAR(testing::integrateVolume(sideways, 1, 0.025), vol + L * section, 2e-4 * vol);
}

TEST(TranslationalSweep, EveryShapeAgreesWithTheBruteForceReference) {
  std::mt19937 rng(7);
  for (ToolShape shape : testing::allShapes()) {
    const Tool tool = makeTool(shape);
    const ToolPart part = makeToolPart(tool, ToolPartKind::kCutter);
    for (int trial = 0; trial < 6; ++trial) {
      glm::dvec3 axis = testing::randomUnit(rng);
      glm::dvec3 move = 6.0 * testing::randomUnit(rng);
      if (trial == 0) axis = {0, 0, 1}, move = {0, 0, -4};  // a plunge on the grid
      if (trial == 1) axis = {0, 0, 1}, move = {5, 3, 0};   // a 3-axis side move
      if (trial == 2) move = -3.0 * axis;                   // a tilted plunge
      if (trial == 3) axis = {0, 0, 1}, move = {4, 0, -2};  // a ramp along x
      const ToolPose a{{0.25, -0.5, 0.1}, axis};
      const glm::dvec3 to = a.tip + move;
      const SweptVolume s = SweptVolume::between(part, a, {to, axis}, 0, 0.01);
      ASSERT_EQ(s.translations().size(), 1u);
      const testing::Sdf sd = sweptSdf(part, a, to);
      const Aabb b = s.bounds();
      int decided = 0;
      for (int dir = 0; dir < 3; ++dir) {
        const int i1 = (dir + 1) % 3;
        const int i2 = (dir + 2) % 3;
        const double du = (b.hi[i1] - b.lo[i1]) / 6.0;
        const double dv = (b.hi[i2] - b.lo[i2]) / 6.0;
        for (double u = b.lo[i1] + du / 4; u < b.hi[i1]; u += du)
          for (double v = b.lo[i2] + dv / 4; v < b.hi[i2]; v += dv)
            decided += testing::checkLine(s, sd, dir, u, v, 1e-7, 1e-7, 0.3);
      }
      EXPECT_GT(decided, 1000) << toolShapeName(shape) << " trial " << trial;
    }
  }
}

TEST(TranslationalSweep, GridAlignedLinesThroughEdgesAndApexes) {
  // Lines exactly through the tool axis, rims and the drill's apex path.
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape), ToolPartKind::kCutter);
    const ToolPose a{{0.0, 0.0, 0.0}, {0, 0, 1}};
    for (const glm::dvec3& to : {glm::dvec3(0, 0, -4), glm::dvec3(4, 0, 0), glm::dvec3(4, 0, -2)}) {
      const SweptVolume s = SweptVolume::between(part, a, {to, {0, 0, 1}}, 0, 0.01);
      const testing::Sdf sd = sweptSdf(part, a, to);
      for (double u : {-3.0, -1.0, 0.0, 1.0, 3.0})
        for (double v : {-3.0, 0.0, 3.0}) {
          testing::checkLine(s, sd, 2, u, v, 1e-7, 1e-7, 0.25);
          testing::checkLine(s, sd, 0, u, v + 3.0, 1e-7, 1e-7, 0.25);
          testing::checkLine(s, sd, 1, v + 3.0, u, 1e-7, 1e-7, 0.25);
        }
      std::vector<Interval> out;
      s.lineIntervals(2, to.x, 0.0, out);  // the axis line at the end of the move
      ASSERT_EQ(out.size(), 1u);
      EXPECT_DOUBLE_EQ(out[0].lo, to.z) << toolShapeName(shape);
      // The top: the start's flutes, unless the line only enters the tool after it fell
      // (the ramp: the rim reaches x = 4 a quarter of the way, 0.5 lower).
      EXPECT_DOUBLE_EQ(out[0].hi, to.z < 0 && to.x > 0 ? 11.5 : 12.0);
    }
  }
}

TEST(TranslationalSweep, LinesThroughTheTrackOfATiltedDrillsApex) {
  // Tilted less than the cone's half angle, the apex is the lowest point: a z line
  // through its track starts exactly there, for every fraction of the move.
  const ToolPart part = makeToolPart(makeTool(ToolShape::kDrill), ToolPartKind::kCutter);
  const glm::dvec3 w = glm::normalize(glm::dvec3(0.2, -0.3, 1.0));
  const ToolPose a{{0.1, 0.2, 0.3}, w};
  const glm::dvec3 to{3.7, -1.9, 0.3};
  const SweptVolume s = SweptVolume::between(part, a, {to, w}, 0, 0.01);
  const testing::Sdf sd = sweptSdf(part, a, to);
  std::vector<Interval> out;
  for (double f = 0.0; f <= 1.0; f += 0.125) {
    const glm::dvec3 apex = a.tip + f * (to - a.tip);
    out.clear();
    s.lineIntervals(2, apex.x, apex.y, out);
    ASSERT_EQ(out.size(), 1u);
    // A tangent contact: its root is ill-conditioned, about sqrt(machine epsilon) * size.
    EXPECT_NEAR(out[0].lo, 0.3, 1e-7) << f;
    testing::checkLine(s, sd, 2, apex.x, apex.y, 1e-7, 1e-7, 0.05);
  }
}

TEST(TranslationalSweep, HolderStackSweepsIntoSeparateIntervals) {
  // Holder cylinders radius 10 (z 35..50) and 15 (z 25..35) above the tip, moved 3 in x:
  // a z line at x 14 meets only the wider, lower one; at x 5, both, merged.
  const ToolPart part = makeToolPart(makeTool(ToolShape::kFlat), ToolPartKind::kHolder);
  const SweptVolume s =
      SweptVolume::between(part, {{0, 0, 0}, {0, 0, 1}}, {{3, 0, 0}, {0, 0, 1}}, 0, 0.01);
  std::vector<Interval> out;
  s.lineIntervals(2, 14.0, 0.0, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].lo, 25.0);
  EXPECT_DOUBLE_EQ(out[0].hi, 35.0);
  out.clear();
  s.lineIntervals(2, 5.0, 0.0, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].lo, 25.0);
  EXPECT_DOUBLE_EQ(out[0].hi, 50.0);
  // A tilted holder: an x line can cross the two cylinders apart.
  const glm::dvec3 w = glm::normalize(glm::dvec3(1, 0, 1));
  const SweptVolume t = SweptVolume::at(part, {{0, 0, 0}, w});
  const testing::Sdf sd = [&](const glm::dvec3& p) {
    return signedDistance(part, {{0, 0, 0}, w}, p);
  };
  int twoPieces = 0;
  for (double z = 15.0; z < 40.0; z += 0.5) {
    out.clear();
    t.lineIntervals(0, 0.0, z, out);
    twoPieces += out.size() == 2;
    testing::checkLine(t, sd, 0, 0.0, z, 1e-9, 1e-9, 0.05);
  }
  EXPECT_GT(twoPieces, 0);
}

TEST(TranslationalSweep, BoundsContainTheSweep) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBull), ToolPartKind::kCutter);
  const ToolPose a{{1, 2, 3}, glm::normalize(glm::dvec3(1, 1, 1))};
  const SweptVolume s = SweptVolume::between(part, a, {{4, -2, 0}, a.axis}, 0, 0.01);
  const Aabb b = s.bounds();
  std::vector<Interval> out;
  for (int axis = 0; axis < 3; ++axis) {
    const int i1 = (axis + 1) % 3;
    const int i2 = (axis + 2) % 3;
    for (double u = b.lo[i1] - 1; u < b.hi[i1] + 1; u += 0.2)
      for (double v = b.lo[i2] - 1; v < b.hi[i2] + 1; v += 0.2) {
        out.clear();
        s.lineIntervals(axis, u, v, out);
        if (out.empty()) continue;
        EXPECT_TRUE(u >= b.lo[i1] && u <= b.hi[i1] && v >= b.lo[i2] && v <= b.hi[i2]);
        EXPECT_GE(out.front().lo, b.lo[axis]);
        EXPECT_LE(out.back().hi, b.hi[axis]);
      }
  }
}

}  // namespace
}  // namespace mdhd::geom

namespace mdhd::geom {
namespace {

TEST(TranslationalSweep, DegenerateMovesStayFiniteAndConsistent) {
  // Zero, tiny and huge moves, far from the origin, every part kind: intervals are
  // finite, sorted and disjoint, and agree with the signed-distance reference.
  const ToolPart parts[] = {
      makeToolPart(testing::makeTool(ToolShape::kBull), ToolPartKind::kCutter),
      makeToolPart(testing::makeTool(ToolShape::kDrill), ToolPartKind::kCutter),
      makeToolPart(testing::makeTool(ToolShape::kBall), ToolPartKind::kHolder)};
  const glm::dvec3 far{-250.0, 480.0, 120.0};
  const glm::dvec3 w = glm::normalize(glm::dvec3(0.1, 0.0, 1.0));
  for (const ToolPart& part : parts)
    for (const glm::dvec3& move :
         {glm::dvec3(0.0), glm::dvec3(1e-9, 0, 0), glm::dvec3(0, 0, 1e-7), glm::dvec3(0, 300, 0)}) {
      const ToolPose a{far, w};
      const SweptVolume s = SweptVolume::between(part, a, {far + move, w}, 0, 0.01);
      ASSERT_EQ(s.translations().size(), 1u);
      const testing::Sdf sd = sweptSdf(part, a, far + move);
      for (double du = -12; du <= 12; du += 4.0)
        for (double dv = -4; dv <= 60; dv += 16.0) {
          testing::checkLine(s, sd, 2, far.x + du, far.y + dv * 0.1, 1e-6, 1e-6, 0.7);
          testing::checkLine(s, sd, 0, far.y + du, far.z + dv, 1e-6, 1e-6, 0.7);
        }
    }
}

TEST(TranslationalSweep, PrismBandIsWhereEverySectionIsTheWidestDisk) {
  // A ball (R 3, flutes 12) on +z moving down and sideways: from z = 1 to z = -1. Its
  // sections are the stadium for max(tip z) + R <= c <= min(tip z) + flutes.
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall), ToolPartKind::kCutter);
  const glm::dvec3 z(0, 0, 1);
  const SweptVolume s = SweptVolume::between(part, {{0, 0, 1}, z}, {{4, 1, -1}, z}, 0, 0.01);
  int axis = -1;
  double lo = 0, hi = 0;
  ASSERT_TRUE(s.prismBand(axis, lo, hi));
  EXPECT_EQ(axis, 2);
  EXPECT_NEAR(lo, 1.0 + 3.0, 1e-12);
  EXPECT_NEAR(hi, -1.0 + 12.0, 1e-12);
  // Lines along x and y at heights inside it meet the sweep alike; just below it, the
  // ball's sections are smaller.
  // The line along x (0) or y (1) at `across` on the other horizontal axis, height c.
  const auto line = [&](int along, double across, double c) {
    std::vector<Interval> out;
    if (along == 0)
      s.lineIntervals(0, across, c, out);
    else
      s.lineIntervals(1, c, across, out);
    return out;
  };
  for (int along : {0, 1}) {
    const std::vector<Interval> ref = line(along, 0.7, lo);
    ASSERT_EQ(ref.size(), 1u);
    for (double c = lo; c <= hi; c += 0.37) {
      const std::vector<Interval> at = line(along, 0.7, c);
      ASSERT_EQ(at.size(), 1u) << c;
      EXPECT_NEAR(at[0].lo, ref[0].lo, 1e-12) << c;
      EXPECT_NEAR(at[0].hi, ref[0].hi, 1e-12) << c;
    }
    // Below it (0.5 over the first tip) the ball's smaller sections show.
    const std::vector<Interval> below = line(along, 0.7, 1.5);
    ASSERT_EQ(below.size(), 1u);
    EXPECT_GT(std::abs(below[0].lo - ref[0].lo) + std::abs(below[0].hi - ref[0].hi), 0.1);
  }
  // An upside-down tool (-z): the band mirrors.
  const SweptVolume down = SweptVolume::between(part, {{0, 0, 10}, -z}, {{1, 0, 10}, -z}, 0, 0.01);
  ASSERT_TRUE(down.prismBand(axis, lo, hi));
  EXPECT_EQ(axis, 2);
  EXPECT_NEAR(lo, 10.0 - 12.0, 1e-12);
  EXPECT_NEAR(hi, 10.0 - 3.0, 1e-12);
}

TEST(TranslationalSweep, NoPrismBandOffTheGridAxesOrWhenTheAxisTurns) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall), ToolPartKind::kCutter);
  int axis = -1;
  double lo = 0, hi = 0;
  const glm::dvec3 tilted = glm::normalize(glm::dvec3(0.1, 0, 1));
  EXPECT_FALSE(SweptVolume::between(part, {{0, 0, 0}, tilted}, {{3, 0, 0}, tilted}, 0, 0.01)
                   .prismBand(axis, lo, hi));
  EXPECT_FALSE(SweptVolume::between(part, {{0, 0, 0}, {0, 0, 1}}, {{3, 0, 0}, tilted}, 0, 0.01)
                   .prismBand(axis, lo, hi));
  // A move longer along the axis than the cylinder: no level is cylinder all the way.
  EXPECT_FALSE(SweptVolume::between(part, {{0, 0, 0}, {0, 0, 1}}, {{0, 0, 20}, {0, 0, 1}}, 0, 0.01)
                   .prismBand(axis, lo, hi));
}

}  // namespace
}  // namespace mdhd::geom

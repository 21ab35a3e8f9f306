// The fresh region of a translated part holds every point its sweep adds to the
// start pose, for every tool shape and move direction, and leaves out the trailing
// half of a raster step (else it would save nothing). The same for a part turning
// about a point of its axis, and for a turning step's chain of translations.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_fresh_region.h"
#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::makeTool;

bool holds(const FreshRegion& r, const glm::dvec3& p) {
  const Aabb c = r.clip({p - glm::dvec3(1e-9), p + glm::dvec3(1e-9)});
  return c.lo.x <= c.hi.x && c.lo.y <= c.hi.y && c.lo.z <= c.hi.z;
}

// Points of the sweep outside the closed start pose, along random grid lines through the
// sweep's box: ends and middles of what the sweep's intervals add to the stamp's.
std::vector<glm::dvec3> addedPoints(const SweptVolume& s, const SweptVolume& stamp,
                                    std::mt19937& rng, int lines) {
  std::vector<glm::dvec3> out;
  const Aabb b = s.bounds();
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<Interval> si, ti;
  for (int n = 0; n < lines; ++n) {
    const int axis = n % 3, u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double cu = b.lo[u] + uni(rng) * (b.hi[u] - b.lo[u]);
    const double cv = b.lo[v] + uni(rng) * (b.hi[v] - b.lo[v]);
    si.clear();
    ti.clear();
    s.lineIntervals(axis, cu, cv, si);
    stamp.lineIntervals(axis, cu, cv, ti);
    for (const Interval& i : si)
      for (double t : {0.0, 1e-6, 0.25, 0.5, 0.75, 1.0 - 1e-6, 1.0}) {
        const double x = i.lo + t * (i.hi - i.lo);
        bool inStamp = false;
        // The stamp's surface too: the sweep's trailing side lies on it, and a cut
        // (open intervals) leaves it solid either way.
        for (const Interval& j : ti) inStamp = inStamp || (j.lo - 1e-7 <= x && x <= j.hi + 1e-7);
        if (inStamp) continue;
        glm::dvec3 p;
        p[axis] = x;
        p[u] = cu;
        p[v] = cv;
        out.push_back(p);
      }
  }
  return out;
}

TEST(ToolFreshRegion, HoldsEverythingTheSweepAddsForEveryShapeAndMove) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int checked = 0;
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape), ToolPartKind::kCutter);
    for (int trial = 0; trial < 24; ++trial) {
      // Vertical and tilted axes; moves sideways, towards the tip, towards the shank,
      // along the axis and at random.
      const glm::dvec3 axis = trial % 3 == 0 ? glm::dvec3(0, 0, 1) : testing::randomUnit(rng);
      glm::dvec3 move = 4.0 * glm::dvec3(uni(rng), uni(rng), uni(rng));
      if (trial % 4 == 1) move -= glm::dot(move, axis) * axis;  // square to the axis
      if (trial % 4 == 2) move = (2.0 + uni(rng)) * axis;       // along it, towards the shank
      if (trial % 4 == 3) move = move - 3.0 * axis;             // towards the tip
      const ToolPose a{{1.0, 2.0, 3.0}, axis}, b{a.tip + move, axis};
      const auto region = freshRegion(part, a, b);
      ASSERT_TRUE(region.has_value());
      const SweptVolume s = SweptVolume::between(part, a, b, 0, 0.01);
      const SweptVolume stamp = SweptVolume::at(part, a);
      for (const glm::dvec3& p : addedPoints(s, stamp, rng, 300)) {
        ASSERT_TRUE(holds(*region, p)) << "shape " << int(shape) << " trial " << trial << " point "
                                       << p.x << " " << p.y << " " << p.z;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 10000);
}

TEST(ToolFreshRegion, LeavesOutTheTrailingHalfOfARasterStep) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall), ToolPartKind::kCutter);
  // Ball r = 3 on a vertical axis, 0.5 mm along +x, dropping 0.05 mm.
  const ToolPose a{{10.0, 0.0, 0.0}, {0, 0, 1}}, b{{10.5, 0.0, -0.05}, {0, 0, 1}};
  const auto region = freshRegion(part, a, b);
  ASSERT_TRUE(region.has_value());
  EXPECT_FALSE(holds(*region, {8.0, 0.0, 5.0}));    // behind the axis, up the flutes
  EXPECT_FALSE(holds(*region, {9.0, 1.0, 0.5}));    // behind the ball's centre
  EXPECT_TRUE(holds(*region, {12.5, 0.0, 5.0}));    // ahead, up the flutes
  EXPECT_TRUE(holds(*region, {10.5, 0.0, -0.04}));  // the bottom, just ahead
  // A box over the trailing half of the tool's box is missed as a whole.
  const Aabb behind = region->clip({{6.0, -4.0, -1.0}, {9.6, 4.0, 13.0}});
  EXPECT_GT(behind.lo.x, behind.hi.x);
}

// The part turned about the point at `h` on its axis through `pivot`.
ToolPose turned(const glm::dvec3& pivot, double h, const glm::dvec3& axis) {
  return {pivot - h * axis, axis};
}

// An axis `degrees` from `axis`, towards a random direction.
glm::dvec3 tiltedBy(const glm::dvec3& axis, double degrees, std::mt19937& rng) {
  glm::dvec3 side = glm::cross(axis, testing::randomUnit(rng));
  side = glm::normalize(side);
  const double t = degrees * std::acos(-1.0) / 180.0;
  return std::cos(t) * axis + std::sin(t) * side;
}

// Points of T(to) outside T(from) the turn region misses, over random turns of every
// shape: 0 for the region of from -> to, many for the reverse turn's (the check can fail).
int missedByTurns(bool reverse, int& checked) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int missed = 0;
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape, 6.0, 20.0), ToolPartKind::kCutter);
    const double pivotHeights[] = {part.centreHeight(), 0.0, 2.0, 25.0};
    for (int trial = 0; trial < 24; ++trial) {
      const glm::dvec3 from = trial % 3 == 0 ? glm::dvec3(0, 0, 1) : testing::randomUnit(rng);
      // Small turns like a 5-axis step's, and large ones the bounds must hold too.
      const double degrees = trial % 2 == 0   ? 0.05 + uni(rng)
                             : trial % 4 == 1 ? 5.0 + 40.0 * uni(rng)
                                              : 120.0 + 50.0 * uni(rng);  // whole boxes past 2 rad
      const glm::dvec3 to = tiltedBy(from, degrees, rng);
      const double h = pivotHeights[trial % 4];
      const glm::dvec3 pivot{3.0, -1.0, 2.0};
      FreshRegion region;
      if (reverse)
        addTurnRegion(part, h, pivot, to, from, region);
      else
        addTurnRegion(part, h, pivot, from, to, region);
      const SweptVolume after = SweptVolume::at(part, turned(pivot, h, to));
      const SweptVolume before = SweptVolume::at(part, turned(pivot, h, from));
      for (const glm::dvec3& p : addedPoints(after, before, rng, 600)) {
        ++checked;
        if (!holds(region, p)) ++missed;
      }
    }
  }
  return missed;
}

TEST(ToolFreshRegion, HoldsEverythingATurnAddsForEveryShapeAndPivot) {
  int checked = 0;
  EXPECT_EQ(missedByTurns(false, checked), 0);
  EXPECT_GT(checked, 5000);
}

TEST(ToolFreshRegion, TheTurnCheckFailsForTheReverseTurnsRegion) {
  int checked = 0;
  EXPECT_GT(missedByTurns(true, checked), 1000);
}

TEST(ToolFreshRegion, LeavesOutTheSideATurnLeaves) {
  // Ball r = 3, 20 mm of flutes, turning 0.1 degrees about its centre (10 mm up) so
  // that the shank end goes +x: the ball and the flutes below the pivot go -x.
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall, 6.0, 20.0), ToolPartKind::kCutter);
  const double h = part.centreHeight();
  ASSERT_EQ(h, 10.0);
  const double t = 0.1 * std::acos(-1.0) / 180.0;
  FreshRegion region;
  addTurnRegion(part, h, {0, 0, h}, {0, 0, 1}, {std::sin(t), 0, std::cos(t)}, region);
  EXPECT_TRUE(holds(region, {-2.99, 0.0, 3.0}));  // the ball's -x side
  EXPECT_FALSE(holds(region, {2.9, 0.0, 3.0}));   // its +x side
  EXPECT_FALSE(holds(region, {2.9, 0.0, 7.0}));   // the flutes' +x side below the pivot
  EXPECT_TRUE(holds(region, {2.99, 0.0, 17.0}));  // ... and above it
  EXPECT_FALSE(holds(region, {-2.9, 0.0, 17.0}));
  // The trailing half of the lower part's box is missed as a whole.
  const Aabb behind = region.clip({{0.2, -4.0, -1.0}, {4.0, 4.0, 9.0}});
  EXPECT_GT(behind.lo.x, behind.hi.x);
}

// A turning step (SweptVolume::between, midpoint axes) from where the last one left
// the part held: its region holds everything its sweep adds to that held pose.
TEST(ToolFreshRegion, HoldsEverythingATurningStepAddsToTheHeldPose) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int checked = 0;
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape, 6.0, 20.0), ToolPartKind::kCutter);
    for (int trial = 0; trial < 12; ++trial) {
      const glm::dvec3 a0 = testing::randomUnit(rng);
      const ToolPose p0{{0, 0, 0}, a0};
      const ToolPose p1{{0.3 * uni(rng), 0.4, 0.1 * uni(rng)}, tiltedBy(a0, 0.3, rng)};
      const ToolPose p2{p1.tip + glm::dvec3(0.1 * uni(rng), 0.4, 0.1 * uni(rng)),
                        tiltedBy(p1.axis, 0.2 + 2.0 * std::abs(uni(rng)), rng)};
      const SweptVolume first = SweptVolume::between(part, p0, p1, 0, 0.01, SweepEnds::kMidpoints);
      const SweptVolume next = SweptVolume::between(part, p1, p2, 0, 0.01, SweepEnds::kMidpoints);
      ASSERT_GT(next.translations().size(), 1u);
      const Translation& last = first.translations().back();
      const ToolPose held{last.to, last.axis};
      const auto region = freshRegion(part, held, next.translations());
      ASSERT_TRUE(region.has_value());
      for (const glm::dvec3& p : addedPoints(next, SweptVolume::at(part, held), rng, 600)) {
        ASSERT_TRUE(holds(*region, p)) << "shape " << int(shape) << " trial " << trial;
        ++checked;
      }
      // A held pose off the step's pivot is no turn about it: no region.
      EXPECT_FALSE(freshRegion(part, ToolPose{held.tip + glm::dvec3(0.01, 0, 0), held.axis},
                               next.translations()));
    }
  }
  EXPECT_GT(checked, 2000);
}

TEST(ToolFreshRegion, NoneForATurningAxisAndEmptyForNoMove) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kFlat), ToolPartKind::kCutter);
  const ToolPose a{{0, 0, 0}, {0, 0, 1}};
  EXPECT_FALSE(freshRegion(part, a, {{1, 0, 0}, glm::normalize(glm::dvec3(0.1, 0, 1))}));
  const auto still = freshRegion(part, a, a);
  ASSERT_TRUE(still.has_value());
  EXPECT_TRUE(still->pieces.empty());
  EXPECT_FALSE(holds(*still, {0, 0, 1}));
}

}  // namespace
}  // namespace mdhd::geom

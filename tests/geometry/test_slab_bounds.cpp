// LineSolid::boundsIn for swept tools (slab_bounds.h): the box it gives for the part
// of a sweep inside a box holds every point of the sweep there, for every tool shape,
// tilted or not, translated or turning, and is much narrower than the sweep's box
// where a long tool leans.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/slab_bounds.h"
#include "sim/geometry/swept_volume.h"
#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::makeTool;

bool emptyBox(const Aabb& b) {
  return !(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z);
}

// Points of `s` inside `box` along grid lines through it (interval ends and middles,
// clipped to the box) that lie outside `bound`; how many were looked at in `seen`.
int pointsOutside(const SweptVolume& s, const Aabb& box, const Aabb& bound, int lines,
                  std::mt19937& rng, int& seen) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<Interval> out;
  int outside = 0;
  for (int n = 0; n < lines; ++n) {
    const int axis = n % 3, u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double cu = box.lo[u] + uni(rng) * (box.hi[u] - box.lo[u]);
    const double cv = box.lo[v] + uni(rng) * (box.hi[v] - box.lo[v]);
    out.clear();
    s.lineIntervals(axis, cu, cv, out);
    for (const Interval& i : out) {
      const double lo = std::max(i.lo, box.lo[axis]), hi = std::min(i.hi, box.hi[axis]);
      if (!(lo <= hi)) continue;
      for (double x : {lo, 0.5 * (lo + hi), hi}) {
        glm::dvec3 p;
        p[axis] = x;
        p[u] = cu;
        p[v] = cv;
        ++seen;
        bool in = true;
        for (int k = 0; k < 3; ++k) in = in && bound.lo[k] <= p[k] && p[k] <= bound.hi[k];
        outside += !in;
      }
    }
  }
  return outside;
}

TEST(SlabBounds, HoldEverySweptPointInsideTheBoxForEveryShapeAndMove) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int seen = 0, narrower = 0;
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape, 6.0, 20.0), ToolPartKind::kCutter);
    for (int trial = 0; trial < 30; ++trial) {
      const glm::dvec3 axis = trial % 5 == 0 ? glm::dvec3(0, 0, 1) : testing::randomUnit(rng);
      const glm::dvec3 move = 3.0 * glm::dvec3(uni(rng), uni(rng), uni(rng));
      const ToolPose a{{1.0, 2.0, 3.0}, axis};
      // Every third a turning move (a union of translations with in-between axes).
      const glm::dvec3 axisB =
          trial % 3 == 2 ? glm::normalize(axis + 0.3 * testing::randomUnit(rng)) : axis;
      const SweptVolume s = SweptVolume::between(part, a, {a.tip + move, axisB}, 0, 0.01);
      const Aabb all = s.bounds();
      for (int b = 0; b < 6; ++b) {
        // Slabs and small boxes inside the sweep's box, a few grid cells in size.
        Aabb box = all;
        const int k = b % 3;
        const double c = all.lo[k] + (0.5 + 0.5 * uni(rng)) * (all.hi[k] - all.lo[k]);
        box.lo[k] = c - 1.6;
        box.hi[k] = c + 1.6;
        if (b >= 3)
          for (int j = 0; j < 3; ++j)
            if (j != k) {
              const double m = 0.5 * (all.lo[j] + all.hi[j]) + 2.0 * uni(rng);
              box.lo[j] = m - 2.0;
              box.hi[j] = m + 2.0;
            }
        const Aabb bound = s.boundsIn(box);
        if (emptyBox(bound)) {
          // Nothing there: no line through the box meets the sweep inside it.
          int none = 0;
          EXPECT_EQ(pointsOutside(s, box, Aabb{box.hi, box.lo}, 60, rng, none), 0);
          EXPECT_EQ(none, 0) << "shape " << int(shape) << " trial " << trial << " box " << b;
          continue;
        }
        for (int j = 0; j < 3; ++j) {
          EXPECT_GE(bound.lo[j], box.lo[j]);
          EXPECT_LE(bound.hi[j], box.hi[j]);
        }
        ASSERT_EQ(pointsOutside(s, box, bound, 150, rng, seen), 0)
            << "shape " << int(shape) << " trial " << trial << " box " << b;
        double clipped = 1.0, tight = 1.0;
        for (int j = 0; j < 3; ++j) {
          clipped *= std::min(all.hi[j], box.hi[j]) - std::max(all.lo[j], box.lo[j]);
          tight *= bound.hi[j] - bound.lo[j];
        }
        narrower += tight < 0.9 * clipped;
      }
    }
  }
  EXPECT_GT(seen, 20000);
  EXPECT_GT(narrower, 100);  // not only the sweep's box clipped
}

// A 6 mm ball on 20 mm of flutes leaning 15 degrees, moved 0.5 mm: in a brick 3.2 mm
// tall at the tip, the tool is the ball and a little of the shank above it, not the
// whole lean of the shank above the brick.
TEST(SlabBounds, ALeaningToolInABrickAtItsTipIsNarrow) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall, 6.0, 20.0), ToolPartKind::kCutter);
  const glm::dvec3 axis = glm::normalize(glm::dvec3(std::tan(15.0 * testing::kPi / 180.0), 0, 1));
  const ToolPose a{{0.0, 0.0, 0.0}, axis}, b{{0.0, 0.5, 0.0}, axis};
  const SweptVolume s = SweptVolume::between(part, a, b, 0, 0.01);
  const Aabb all = s.bounds();
  const Aabb brick{{-10.0, -10.0, -0.2}, {20.0, 10.0, 3.0}};
  const Aabb bound = s.boundsIn(brick);
  EXPECT_GT(all.hi.x, 7.8);  // the flutes lean 20 sin 15 = 5.2 mm over the ball
  const double c = std::cos(15.0 * testing::kPi / 180.0),
               sn = std::sin(15.0 * testing::kPi / 180.0);
  // The disks square to the axis reach 3 cos 15 along x from it, 3 sin 15 along z: the
  // axis at the brick's top and that much above it, (3 + 3 sin 15) / cos 15 from the
  // tip, is the furthest a point of the tool in the brick can lean.
  EXPECT_NEAR(bound.lo.x, -3.0 * c, 1e-6);
  EXPECT_NEAR(bound.hi.x, (3.0 + 3.0 * sn) / c * sn + 3.0 * c, 1e-6);
  EXPECT_NEAR(bound.lo.z, -0.2, 1e-12);
  EXPECT_NEAR(bound.hi.z, 3.0, 1e-12);
  // Above the whole tool: nothing.
  EXPECT_TRUE(emptyBox(s.boundsIn({{-10, -10, 40}, {20, 10, 45}})));
}

TEST(SlabBounds, AStampAndAnUprightPieceClipToTheirDisks) {
  // An upright cylinder of radius 2 from z 1 to 5 at (1, 1): inside a box cutting it
  // at z 2..3 and x <= 2 it is x in [-1, 2], y in [-1, 3], z in [2, 3].
  const Aabb b =
      sweptPieceBoundsIn({1, 1, 0}, {0, 0, 0}, {0, 0, 1}, 1.0, 5.0, 2.0, {{-5, -5, 2}, {2, 5, 3}});
  EXPECT_NEAR(b.lo.x, -1.0, 1e-8);
  EXPECT_DOUBLE_EQ(b.hi.x, 2.0);
  EXPECT_NEAR(b.lo.y, -1.0, 1e-8);
  EXPECT_NEAR(b.hi.y, 3.0, 1e-8);
  EXPECT_DOUBLE_EQ(b.lo.z, 2.0);
  EXPECT_DOUBLE_EQ(b.hi.z, 3.0);
  // Below it: empty.
  const Aabb below = sweptPieceBoundsIn({1, 1, 0}, {0, 0, 0}, {0, 0, 1}, 1.0, 5.0, 2.0,
                                        {{-5, -5, -3}, {5, 5, 0.5}});
  EXPECT_TRUE(emptyBox(below));
}

}  // namespace
}  // namespace mdhd::geom

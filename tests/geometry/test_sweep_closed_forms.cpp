// The closed forms for translations along a grid axis (lines along the tool's axis and
// square to it) against the general section solver and a brute-force membership
// reference: random moves, every shape and part, all six axis signs, grazing lines.
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/string_cast.hpp>

#include "sim/geometry/axial_sweep.h"
#include "sim/geometry/swept_volume.h"
#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::makeTool;

// Length of the points in exactly one of the two sorted, disjoint interval lists.
double symmetricDifference(const std::vector<Interval>& a, const std::vector<Interval>& b) {
  std::vector<std::pair<double, int>> ends;
  for (const Interval& i : a) ends.push_back({i.lo, 1}), ends.push_back({i.hi, -1});
  for (const Interval& i : b) ends.push_back({i.lo, 2}), ends.push_back({i.hi, -2});
  std::sort(ends.begin(), ends.end());
  double sum = 0.0;
  int inA = 0, inB = 0;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const int e = ends[k].second;
    inA += e == 1 ? 1 : e == -1 ? -1 : 0;
    inB += e == 2 ? 1 : e == -2 ? -1 : 0;
    if ((inA > 0) != (inB > 0)) sum += ends[k + 1].first - ends[k].first;
  }
  return sum;
}

struct Stats {
  int lines = 0;
  int hits = 0;
};

// Every line through a grid over the sweep's box, plus the lines that graze the tool
// at both ends of the move: closed forms and general solver must agree.
void compareSweep(const SweptVolume& s, const std::vector<ToolPose>& ends, double radius,
                  std::mt19937& rng, Stats& stats, const std::string& what) {
  const Aabb b = s.bounds();
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<Interval> fast;
  std::vector<Interval> general;
  auto check = [&](int axis, double u, double v, bool grazing) {
    fast.clear();
    general.clear();
    s.lineIntervals(axis, u, v, fast);
    s.generalLineIntervals(axis, u, v, general);
    ++stats.lines;
    stats.hits += !fast.empty();
    // Through a cone's apex or along a tangent the general solver's tolerances decide.
    ASSERT_LE(symmetricDifference(fast, general), grazing ? 1e-5 : 1e-6)
        << what << " axis " << axis << " u " << u << " v " << v << "\n fast "
        << ::testing::PrintToString(fast.size()) << " " << (fast.empty() ? 0.0 : fast[0].lo) << " "
        << (fast.empty() ? 0.0 : fast[0].hi) << "\n general " << general.size() << " "
        << (general.empty() ? 0.0 : general[0].lo) << " "
        << (general.empty() ? 0.0 : general[0].hi);
    for (std::size_t i = 0; i < fast.size(); ++i) {
      EXPECT_LT(fast[i].lo, fast[i].hi) << what << " axis " << axis << " u " << u << " v " << v;
      if (i > 0) {
        EXPECT_LT(fast[i - 1].hi, fast[i].lo);
      }
    }
    // The same intervals to rounding; a chord that only grazes the surface has ends
    // as sensitive as a square root (both solvers).
    if (fast.size() == general.size())
      for (std::size_t i = 0; i < fast.size(); ++i) {
        const double tol = grazing ? 1e-5 : general[i].hi - general[i].lo > 1e-3 ? 1e-9 : 1e-6;
        EXPECT_NEAR(fast[i].lo, general[i].lo, tol) << what << " axis " << axis;
        EXPECT_NEAR(fast[i].hi, general[i].hi, tol) << what << " axis " << axis;
      }
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int i1 = (axis + 1) % 3;
    const int i2 = (axis + 2) % 3;
    for (int k = 0; k < 150; ++k) {
      const double u = b.lo[i1] + (b.hi[i1] - b.lo[i1]) * (1.2 * uni(rng) - 0.1);
      const double v = b.lo[i2] + (b.hi[i2] - b.lo[i2]) * (1.2 * uni(rng) - 0.1);
      check(axis, u, v, false);
    }
    // Grazing: tangent to the widest radius, through the axis, at piece heights.
    for (const ToolPose& p : ends)
      for (int k = 0; k < 8; ++k) {
        const double phi = 2.0 * testing::kPi * k / 8;
        check(axis, p.tip[i1] + radius * std::cos(phi), p.tip[i2] + radius * std::sin(phi), true);
        check(axis, p.tip[i1], p.tip[i2] + radius * (k - 4) / 4.0, true);
        check(axis, p.tip[i1] + radius * (k - 4) / 4.0, p.tip[i2], true);
      }
  }
}

TEST(SweepClosedForms, AgreeWithTheGeneralSolver) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const glm::dvec3 gridAxes[] = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0},
                                 {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}};
  Stats stats;
  for (ToolShape shape : testing::allShapes())
    for (ToolPartKind kind : {ToolPartKind::kCutter, ToolPartKind::kShank, ToolPartKind::kHolder}) {
      Tool tool = makeTool(shape, 6.0, 12.0);
      if (shape == ToolShape::kDrill) tool.tip_angle = 90.0;  // 45-degree flanks: degenerate
      const ToolPart part = makeToolPart(tool, kind);
      if (part.empty()) continue;
      for (int trial = 0; trial < 24; ++trial) {
        const glm::dvec3 w = gridAxes[trial % 6];
        glm::dvec3 move(uni(rng), uni(rng), uni(rng));
        move *= 6.0;
        switch (trial / 6) {
          case 0:  // along the axis (a plunge)
            move = 4.0 * uni(rng) * w;
            break;
          case 1:  // square to the axis
            move -= glm::dot(move, w) * w;
            break;
          case 2:  // 45 degrees to the axis, as the drill's flanks
            move = 3.0 * glm::normalize(glm::normalize(move - glm::dot(move, w) * w) + w);
            break;
          default:
            break;
        }
        if (trial == 23) move = glm::dvec3(0.0);  // a stamp
        const ToolPose a{{uni(rng), uni(rng), uni(rng)}, w};
        const ToolPose b{a.tip + move, w};
        const SweptVolume s = SweptVolume::between(part, a, b, 0, 0.01);
        compareSweep(s, {a, b}, part.bodies.back().pieces.back().maxRadius(), rng, stats,
                     std::string(toolShapeName(shape)) + " part " +
                         std::to_string(static_cast<int>(kind)) + " trial " +
                         std::to_string(trial) + " from " + glm::to_string(a.tip) + " by " +
                         glm::to_string(move));
        if (HasFatalFailure()) return;
      }
    }
  EXPECT_GT(stats.lines, 50000);
  EXPECT_GT(stats.hits, stats.lines / 4);
}

TEST(SweepClosedForms, TiltedAndTurningStepsAgreeWithTheGeneralSolver) {
  // No closed form applies: the band form of the section solver against its general
  // candidate enumeration, on random tilts, moves and 5-axis turns.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Stats stats;
  for (ToolShape shape : testing::allShapes())
    for (int trial = 0; trial < 12; ++trial) {
      const ToolPart part = makeToolPart(makeTool(shape, 6.0, 12.0), ToolPartKind::kCutter);
      glm::dvec3 w = testing::randomUnit(rng);
      if (trial == 0) w = glm::normalize(glm::dvec3(0.0, 0.3, 1.0));  // square to x lines
      const ToolPose a{{uni(rng), uni(rng), uni(rng)}, w};
      glm::dvec3 move = 5.0 * testing::randomUnit(rng);
      if (trial == 1) move = 3.0 * w;  // a tilted plunge
      glm::dvec3 w2 = w;
      if (trial >= 6) w2 = glm::normalize(w + 0.3 * testing::randomUnit(rng));  // a 5-axis turn
      const ToolPose b{a.tip + move, w2};
      const SweptVolume s = SweptVolume::between(part, a, b, 0, 0.05);
      compareSweep(s, {a, b}, 3.0, rng, stats,
                   std::string(toolShapeName(shape)) + " trial " + std::to_string(trial));
      if (HasFatalFailure()) return;
    }
  EXPECT_GT(stats.hits, stats.lines / 4);
}

TEST(SweepClosedForms, BullCornerOfManyPiecesAgrees) {
  // A fine corner tolerance: dozens of frustums, the lowest point found among them.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Tool tool = makeTool(ToolShape::kBull, 10.0, 20.0);
  tool.corner_radius = 2.5;
  const ToolPart part = makeToolPart(tool, ToolPartKind::kCutter, 1e-5);
  ASSERT_GT(part.bodies[0].pieces.size(), 40u);
  Stats stats;
  for (int trial = 0; trial < 20; ++trial) {
    const ToolPose a{{uni(rng), uni(rng), uni(rng)}, {0, 0, 1}};
    const glm::dvec3 move = 5.0 * glm::dvec3(uni(rng), uni(rng), uni(rng));
    const SweptVolume s = SweptVolume::between(part, a, {a.tip + move, {0, 0, 1}}, 0, 0.01);
    compareSweep(s, {a}, 5.0, rng, stats, "bull trial " + std::to_string(trial));
    if (HasFatalFailure()) return;
  }
}

TEST(SweepClosedForms, ProfilesOfEveryToolShape) {
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape), ToolPartKind::kCutter);
    const std::optional<AxialProfile> p = axialProfile(part.bodies[0]);
    ASSERT_TRUE(p.has_value()) << toolShapeName(shape);
    EXPECT_DOUBLE_EQ(p->maxRadius, 3.0);
    EXPECT_DOUBLE_EQ(p->top, 12.0);
    // The lowest point at a radius: the flat bottom, the ball, the cone (118 degrees).
    const double atTwo = p->lowAt(4.0);
    switch (shape) {
      case ToolShape::kFlat:
        EXPECT_EQ(atTwo, 0.0);
        break;
      case ToolShape::kBall:
        EXPECT_NEAR(atTwo, 3.0 - std::sqrt(5.0), 1e-12);
        break;
      case ToolShape::kBull:  // flat to radius 2, then the corner
        EXPECT_NEAR(atTwo, 0.0, 1e-12);
        EXPECT_NEAR(p->lowAt(2.5 * 2.5), 1.0 - std::sqrt(1.0 - 0.25), 1e-3);
        break;
      case ToolShape::kDrill:
        EXPECT_NEAR(atTwo, 2.0 / std::tan(59.0 * testing::kPi / 180.0), 1e-12);
        break;
    }
  }
  // A body that narrows upwards has no profile: the general solver takes it.
  ConvexBody narrowing{{frustumPiece(0.0, 2.0, 3.0, 1.0)}};
  EXPECT_FALSE(axialProfile(narrowing).has_value());
  ConvexBody dented{{cylinderPiece(0.0, 1.0, 1.0), frustumPiece(1.0, 2.0, 1.0, 2.0)}};
  EXPECT_FALSE(axialProfile(dented).has_value());
  ConvexBody fullSphere{{spherePiece(1.0, 1.0, 0.0, 2.0)}};
  EXPECT_FALSE(axialProfile(fullSphere).has_value());
}

TEST(SweepClosedForms, NarrowingBodiesStillAgreeThroughTheGeneralSolver) {
  // A ball on a cone that narrows upwards (no profile) swept sideways and down.
  ToolPart part;
  part.bodies.push_back(
      ConvexBody{{spherePiece(1.0, 1.0, 0.0, 1.0), spherePiece(1.0, 1.0, 1.0, 2.0)}});
  std::mt19937 rng(3);
  Stats stats;
  const ToolPose a{{0.1, 0.2, 0.3}, {0, 0, 1}};
  const ToolPose b{{2.1, -0.7, 0.3}, {0, 0, 1}};
  const SweptVolume s = SweptVolume::between(part, a, b, 0, 0.01);
  compareSweep(s, {a, b}, 1.0, rng, stats, "sphere");
  // The whole sphere swept is a capsule: a z line through both centres' track.
  std::vector<Interval> out;
  s.lineIntervals(2, 0.1, 0.2, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].lo, 0.3, 1e-9);
  EXPECT_NEAR(out[0].hi, 2.3, 1e-9);
}

}  // namespace
}  // namespace mdhd::geom

// Adaptive stepping: enough steps that the tool's chords stay within tolerance,
// and no more than the analytic count where there is one.
#include "sim/kinematics/adaptive_steps.h"

#include <cmath>
#include <numbers>

#include "sim/kinematics/presets.h"
#include "tests/kinematics/expect_vec.h"
#include "tests/kinematics/joint_moves.h"

namespace mdhd::kin {
namespace {

JointValues joints(double x, double y, double z, double a = 0, double b = 0, double c = 0) {
  return {x, y, z, a, b, c, 0, 0, 0};
}

using test_support::move;

double pointToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 d = b - a;
  const double len2 = glm::dot(d, d);
  const double t = len2 > 0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * d));
}

// The largest distance, over tool points at the tip and `reach` above it (on the axis and
// `reach` off it), between the true motion and the chords of n equal steps.
double chordError(const JointPath& path, int n, double reach) {
  const Kinematics& kin = path.kinematics();
  const double len = path.toolLength();
  const glm::dvec3 points[] = {
      {0, 0, -len}, {0, 0, reach - len}, {reach, 0, -len}, {0, reach, -len}};
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    const Rigid a = kin.toolInWorkpiece(path.at(double(i) / n));
    const Rigid b = kin.toolInWorkpiece(path.at(double(i + 1) / n));
    for (int k = 1; k < 16; ++k) {
      const Rigid mid = kin.toolInWorkpiece(path.at((i + k / 16.0) / n));
      for (const glm::dvec3& p : points) {
        worst = std::max(worst, pointToSegment(mid.point(p), a.point(p), b.point(p)));
      }
    }
  }
  return worst;
}

TEST(AdaptiveSteps, StraightMovesNeedOneStep) {
  const Kinematics mill(presets::threeAxisMill());
  EXPECT_EQ(
      adaptiveSteps(JointPath(mill, move(joints(0, 0, 0), joints(100, -50, 20)), 50), 80, 0.001),
      1);
  // A trunnion machine moving only linear joints is still a translation in W.
  const Kinematics ac(presets::acTrunnion());
  EXPECT_EQ(
      adaptiveSteps(
          JointPath(ac, move(joints(0, 0, 0, -30, 0, 45), joints(100, -50, 20, -30, 0, 45)), 50),
          80, 0.001),
      1);
}

TEST(AdaptiveSteps, FullCircleMatchesTheSagittaFormula) {
  const Kinematics mill(presets::threeAxisMill());
  gcode::Motion m = move(joints(10, 0, 0), joints(10, 0, 0));
  m.type = gcode::MotionType::kArc;
  m.turn = 1;
  const JointPath p(mill, m, 20);
  // Radius 10, tolerance 0.01: r (2 pi / n)^2 / 8 <= 0.01 -> n >= 2 pi sqrt(125) = 70.25.
  const int n = adaptiveSteps(p, 0, 0.01);
  EXPECT_EQ(n, 71);
  EXPECT_LE(chordError(p, n, 0), 0.01);
  EXPECT_GT(chordError(p, n - 20, 0), 0.01);  // far fewer would not do
}

TEST(AdaptiveSteps, RotaryMovesKeepEveryToolPointWithinTolerance) {
  struct Case {
    Machine machine;
    gcode::Motion motion;
    bool tcp;
  };
  const Case cases[] = {
      {presets::acTrunnion(), move(joints(0, 0, 100), joints(20, 0, 100, -90, 0, 30)), false},
      {presets::bcHeadTable(), move(joints(0, 0, 100), joints(0, 0, 100, 0, 60, 0)), false},
      {presets::nutatingB45(), move(joints(0, 0, 100), joints(10, 0, 90, 0, 180, 90)), false},
      {presets::acTrunnion(), move(joints(0, -100, 100), joints(0, -100, 100, -90, 0, 0)), true},
  };
  for (const Case& c : cases) {
    const Kinematics kin(c.machine);
    gcode::Motion m = c.motion;
    m.tcp = c.tcp;
    const JointPath p(kin, m, 50);
    for (double tol : {0.1, 0.01}) {
      const int n = adaptiveSteps(p, 80, tol);
      SCOPED_TRACE(kin.machine().name + " tol " + std::to_string(tol));
      EXPECT_GT(n, 1);
      EXPECT_LE(chordError(p, n, 80), tol);
      // Not wildly more than needed: half the steps already break the tolerance.
      EXPECT_GT(chordError(p, std::max(1, n / 3), 80), tol);
    }
  }
}

TEST(AdaptiveSteps, BadArgumentsAndCap) {
  const Kinematics mill(presets::threeAxisMill());
  const JointPath p(mill, move(joints(0, 0, 0), joints(1, 0, 0)), 10);
  EXPECT_THROW(adaptiveSteps(p, 10, 0), KinematicsError);
  EXPECT_THROW(adaptiveSteps(p, 10, std::nan("")), KinematicsError);
  EXPECT_THROW(adaptiveSteps(p, -1, 0.1), KinematicsError);
  gcode::Motion m = move(joints(10, 0, 0), joints(10, 0, 0));
  m.type = gcode::MotionType::kArc;
  m.turn = 50;
  EXPECT_EQ(adaptiveSteps(JointPath(mill, m, 10), 0, 1e-9, 1000), 1000);
}

}  // namespace
}  // namespace mdhd::kin

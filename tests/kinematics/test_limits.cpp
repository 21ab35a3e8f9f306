// Limit checks of joint vectors and of whole paths, including excursions that only
// happen between the end points.
#include "sim/kinematics/limits.h"

#include <cmath>
#include <numbers>
#include <random>

#include "sim/kinematics/presets.h"
#include "tests/kinematics/expect_vec.h"
#include "tests/kinematics/joint_moves.h"

namespace mdhd::kin {
namespace {

using test_support::move;
using test_support::xyz;

// The example 3-axis machine: X -50..550, Y -50..450, Z -100..300.
Machine exampleMill() {
  Machine m = presets::threeAxisMill();
  m.joints[0].limits = Limits{-50, 550};
  m.joints[1].limits = Limits{-50, 450};
  m.joints[2].limits = Limits{-100, 300};
  return m;
}

TEST(Limits, VectorReportsFirstJointValueAndExcess) {
  const Kinematics kin(exampleMill());
  EXPECT_FALSE(checkLimits(kin, xyz(550, -50, 300)));  // on the limits is fine
  const auto v = checkLimits(kin, xyz(600, 20, -130));
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kX);
  EXPECT_EQ(v->joint, 0);
  EXPECT_EQ(v->value, 600);
  EXPECT_EQ(v->limit, 550);
  EXPECT_EQ(v->excess, 50);
  const auto z = checkLimits(kin, xyz(0, 0, -130));
  ASSERT_TRUE(z);
  EXPECT_EQ(z->axis, gcode::kZ);
  EXPECT_EQ(z->limit, -100);
  EXPECT_EQ(z->excess, 30);
}

TEST(Limits, NanIsNeverInRange) {
  const Kinematics kin(exampleMill());
  const auto v = checkLimits(kin, xyz(0, std::nan(""), 0));
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kY);
}

TEST(Limits, RotaryWithoutLimitsTurnsFreely) {
  const Kinematics kin(presets::acTrunnion());
  JointValues q = xyz(0, 0, 0);
  q[gcode::kC] = 7200;
  EXPECT_FALSE(checkLimits(kin, q));
  q[gcode::kA] = -121;
  const auto v = checkLimits(kin, q);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kA);
  EXPECT_EQ(v->excess, 1);
}

TEST(Limits, LinePathCrossingALimit) {
  const Kinematics kin(exampleMill());
  const JointPath p(kin, move(xyz(500, 0, 0), xyz(600, 0, 0)), 0);
  const auto v = checkLimits(p);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kX);
  EXPECT_DOUBLE_EQ(v->first_s, 0.5);
  EXPECT_EQ(v->worst_s, 1.0);
  EXPECT_EQ(v->value, 600);
  EXPECT_EQ(v->excess, 50);
  EXPECT_FALSE(checkLimits(JointPath(kin, move(xyz(500, 0, 0), xyz(550, 450, 300)), 0)));
}

TEST(Limits, EarliestViolationWinsAcrossJoints) {
  const Kinematics kin(exampleMill());
  // Z goes 200 -> 600 and crosses its max 300 at s = 0.25; X crosses 550 at s = 0.5.
  const JointPath p(kin, move(xyz(500, 0, 200), xyz(600, 0, 600)), 0);
  const auto v = checkLimits(p);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kZ);
  EXPECT_DOUBLE_EQ(v->first_s, 0.25);
  EXPECT_EQ(v->excess, 300);
}

TEST(Limits, AllListsEveryJointThatLeaves) {
  // AC trunnion: X 0 -> 500 and A 0 -> -130 in one move. X leaves at s 0.8 (400), A at
  // 12/13 (-120): both are overtravel, whichever left first.
  const Kinematics kin(presets::acTrunnion());
  JointValues b = xyz(500, 0, 0);
  b[gcode::kA] = -130;
  const JointPath p(kin, move(xyz(0, 0, 0), b), 0);
  const auto all = checkLimitsAll(p);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].axis, gcode::kX);
  EXPECT_DOUBLE_EQ(all[0].first_s, 0.8);
  EXPECT_EQ(all[0].excess, 100);
  EXPECT_TRUE(all[0].outside_at_end);
  EXPECT_EQ(all[1].axis, gcode::kA);
  EXPECT_DOUBLE_EQ(all[1].first_s, 12.0 / 13);
  EXPECT_EQ(all[1].excess, 10);
  EXPECT_TRUE(all[1].outside_at_end);
  // Back: both start beyond (first_s 0, machine order) and end inside.
  const auto back = checkLimitsAll(JointPath(kin, move(b, xyz(0, 0, 0)), 0));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].axis, gcode::kX);
  EXPECT_EQ(back[1].axis, gcode::kA);
  EXPECT_EQ(back[1].first_s, 0);
  EXPECT_FALSE(back[0].outside_at_end);
  EXPECT_FALSE(back[1].outside_at_end);
  EXPECT_EQ(checkLimits(p)->axis, gcode::kX);  // the earliest
}

// From below a joint's min to beyond its max: one entry per side, the min side left at
// once (not outside at the end), the max side with its own crossing and excess. Until
// session 23 this was one entry (the min side) and the max overtravel was lost.
TEST(Limits, AllListsBothSidesOfAJointThatCrosses) {
  const Kinematics kin(exampleMill());  // X -50..550
  const auto all = checkLimitsAll(JointPath(kin, move(xyz(-60, 0, 0), xyz(600, 0, 0)), 0));
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].axis, gcode::kX);
  EXPECT_EQ(all[0].side, -1);
  EXPECT_EQ(all[0].limit, -50);
  EXPECT_EQ(all[0].value, -60);
  EXPECT_EQ(all[0].excess, 10);
  EXPECT_EQ(all[0].first_s, 0);
  EXPECT_FALSE(all[0].outside_at_end);
  EXPECT_EQ(all[1].axis, gcode::kX);
  EXPECT_EQ(all[1].side, 1);
  EXPECT_EQ(all[1].limit, 550);
  EXPECT_EQ(all[1].value, 600);
  EXPECT_EQ(all[1].excess, 50);
  EXPECT_DOUBLE_EQ(all[1].first_s, 610.0 / 660);
  EXPECT_EQ(all[1].worst_s, 1);
  EXPECT_TRUE(all[1].outside_at_end);
  // Staying beyond one side is one entry, still outside at the end.
  const auto same = checkLimitsAll(JointPath(kin, move(xyz(600, 0, 0), xyz(560, 0, 0)), 0));
  ASSERT_EQ(same.size(), 1u);
  EXPECT_EQ(same[0].side, 1);
  EXPECT_EQ(same[0].excess, 50);
  EXPECT_TRUE(same[0].outside_at_end);

  // An arc (sampled) from X-55 over the top to X555 about (250, 100): both sides again.
  gcode::Motion m = move(xyz(-55, 100, 0), xyz(555, 100, 0));
  m.type = gcode::MotionType::kArc;
  m.center = {250, 100};
  m.turn = -1;
  const auto arc = checkLimitsAll(JointPath(kin, m, 0));
  ASSERT_EQ(arc.size(), 2u);
  EXPECT_EQ(arc[0].side, -1);
  EXPECT_NEAR(arc[0].excess, 5, 1e-9);
  EXPECT_EQ(arc[0].first_s, 0);
  EXPECT_FALSE(arc[0].outside_at_end);
  EXPECT_EQ(arc[1].side, 1);
  EXPECT_NEAR(arc[1].excess, 5, 1e-9);
  // X = 250 + 305 cos(pi (1 - s)) reaches 550 where cos = 300 / 305.
  EXPECT_NEAR(arc[1].first_s, 1 - std::acos(300.0 / 305) / std::numbers::pi, 1e-9);
  EXPECT_TRUE(arc[1].outside_at_end);
}

TEST(Limits, ArcThatExceedsOnlyInItsMiddle) {
  const Kinematics kin(exampleMill());
  // G2 from (90, 445) to (110, 445) about (100, 445): clockwise over the top, through
  // (100, 455) at s = 0.5. Y max is 450: both ends are inside. It leaves where
  // 445 + 10 sin(theta) = 450, theta = 5 pi / 6, s = (pi - 5 pi / 6) / pi = 1/6.
  gcode::Motion m = move(xyz(90, 445, 0), xyz(110, 445, 0));
  m.type = gcode::MotionType::kArc;
  m.center = {100, 445};
  m.turn = -1;
  const auto v = checkLimits(JointPath(kin, m, 0));
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kY);
  EXPECT_EQ(v->limit, 450);
  EXPECT_NEAR(v->value, 455, 1e-12);
  EXPECT_NEAR(v->excess, 5, 1e-12);
  EXPECT_NEAR(v->worst_s, 0.5, 1e-9);
  EXPECT_NEAR(v->first_s, 1.0 / 6, 1e-9);
  // The same ends counter-clockwise pass under the centre: clean.
  m.turn = 1;
  EXPECT_FALSE(checkLimits(JointPath(kin, m, 0)));
}

TEST(Limits, ArcGrazingTheLimitIsClean) {
  const Kinematics kin(exampleMill());
  // Top of the circle exactly at Y 450.
  gcode::Motion m = move(xyz(90, 440, 0), xyz(110, 440, 0));
  m.type = gcode::MotionType::kArc;
  m.center = {100, 440};
  m.turn = -1;
  EXPECT_FALSE(checkLimits(JointPath(kin, m, 0)));
}

TEST(Limits, TcpPathBulgesPastALimitMidway) {
  // AC trunnion with Z max 180; under G43.4 the tip stays at (0, -100, 100) in W while A
  // goes 0 -> -90. The tip in the machine is R_x(A) (0, -100, 100), its z
  // 100 (cos A - sin A) = 100 sqrt2 cos(A + 45): 100 at both ends, 141.42 at A-45. The Z
  // joint is that + 50 (tool length): 150, 191.42 at s 0.5, 150.
  Machine mach = presets::acTrunnion();
  mach.joints[2].limits = Limits{-200, 180};
  const Kinematics kin(mach);
  JointValues a = xyz(0, -100, 100);
  JointValues b = a;
  b[gcode::kA] = -90;
  gcode::Motion m = move(a, b);
  m.tcp = true;
  const JointPath p(kin, m, 50);
  EXPECT_NEAR(p.startJoints()[gcode::kZ], 150, 1e-9);
  EXPECT_NEAR(p.endJoints()[gcode::kZ], 150, 1e-9);
  const auto v = checkLimits(p);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kZ);
  EXPECT_NEAR(v->value, 50 + 100 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(v->worst_s, 0.5, 1e-6);
  // 100 sqrt2 cos(A + 45) = 130 -> A = acos(1.3 / sqrt2) - 45 degrees, |A| / 90 = s.
  const double first = (45 - std::acos(1.3 / std::sqrt(2.0)) * 180 / std::numbers::pi) / 90;
  EXPECT_NEAR(v->first_s, first, 1e-9);
}

TEST(Limits, PathStartingOutsideStartsAtZero) {
  const Kinematics kin(exampleMill());
  const auto v = checkLimits(JointPath(kin, move(xyz(-60, 0, 0), xyz(0, 0, 0)), 0));
  ASSERT_TRUE(v);
  EXPECT_EQ(v->first_s, 0);
  EXPECT_EQ(v->worst_s, 0);
  EXPECT_EQ(v->value, -60);
  EXPECT_EQ(v->excess, 10);
}

TEST(Limits, ManyTurnHelixStaysFast) {
  const Kinematics kin(exampleMill());
  // 200 turns ccw of a 10 mm circle about (540, 200) from (530, 200): its far side touches
  // X 550 exactly. Clean, and not slow.
  gcode::Motion m = move(xyz(530, 200, 0), xyz(530, 200, -20));
  m.type = gcode::MotionType::kArc;
  m.center = {540, 200};
  m.turn = 200;
  EXPECT_FALSE(checkLimits(JointPath(kin, m, 0)));
  // Centre (545, 200) from (535, 200): the far side reaches 555. Leaving where
  // 545 + 10 cos(theta) = 550, theta = 5 pi / 3, s = (2 pi / 3) / (400 pi) = 1/600; the
  // first time at 555 is theta = 2 pi, s = 1/400.
  m.start = xyz(535, 200, 0);
  m.end = xyz(535, 200, -20);
  m.center = {545, 200};
  const auto v = checkLimits(JointPath(kin, m, 0));
  ASSERT_TRUE(v);
  EXPECT_EQ(v->axis, gcode::kX);
  EXPECT_NEAR(v->value, 555, 1e-9);
  EXPECT_NEAR(v->first_s, 1.0 / 600, 1e-12);
  EXPECT_NEAR(std::fmod(v->worst_s * 200, 1.0), 0.5, 1e-6);  // a far side; the top is flat
}

// Brute force over a fine grid of s: the earliest crossing and the extreme beyond it.
std::optional<LimitViolation> bruteForce(const JointPath& p, int n) {
  const Machine& m = p.kinematics().machine();
  std::optional<LimitViolation> best;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    if (!m.joints[j].limits) continue;
    const Limits l = *m.joints[j].limits;
    const auto axis = *axisOfName(m.joints[j].name);
    std::optional<LimitViolation> v;
    for (int i = 0; i <= n; ++i) {
      const double s = double(i) / n;
      const double x = p.at(s)[axis];
      const int dir = x > l.max + kLimitSlack ? 1 : (x < l.min - kLimitSlack ? -1 : 0);
      if (dir == 0) continue;
      if (!v) {
        v = LimitViolation{int(j), axis, dir > 0 ? l.max : l.min, x, 0, s, s};
      } else if ((v->limit == l.max) == (dir > 0) && dir * (x - v->value) > 0) {
        v->value = x, v->worst_s = s;
      }
    }
    if (v && (!best || v->first_s < best->first_s)) best = v;
  }
  return best;
}

TEST(Limits, RandomArcsAndTcpMovesAgreeWithBruteForce) {
  Machine mach = presets::bcHeadTable();
  mach.joints[0].limits = Limits{-40, 40};
  mach.joints[1].limits = Limits{-40, 40};
  mach.joints[2].limits = Limits{-20, 60};
  const Kinematics kin(mach);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int violations = 0;
  for (int i = 0; i < 60; ++i) {
    gcode::Motion m;
    const bool tcp = i % 2 == 1;
    m.tcp = tcp;
    m.start = xyz(30 * u(rng), 30 * u(rng), 20 + 20 * u(rng));
    m.end = xyz(30 * u(rng), 30 * u(rng), 20 + 20 * u(rng));
    m.start[gcode::kB] = 60 * u(rng);
    m.end[gcode::kB] = 60 * u(rng);
    m.end[gcode::kC] = 180 * u(rng);
    if (i % 3 == 0) {
      m.type = gcode::MotionType::kArc;
      m.turn = u(rng) > 0 ? 1 : -1;
      m.center = {(m.start[0] + m.end[0]) / 2 + 10 * u(rng), (m.start[1] + m.end[1]) / 2};
      // Same radius at both ends: put the end on the start's circle.
      const double r = std::hypot(m.start[0] - m.center[0], m.start[1] - m.center[1]);
      const double a = std::numbers::pi * u(rng);
      m.end[0] = m.center[0] + r * std::cos(a);
      m.end[1] = m.center[1] + r * std::sin(a);
    } else {
      m.type = gcode::MotionType::kFeed;
    }
    const JointPath p(kin, m, 30);
    const auto got = checkLimits(p);
    const auto want = bruteForce(p, 10000);
    SCOPED_TRACE(i);
    ASSERT_EQ(got.has_value(), want.has_value());
    if (!got) continue;
    ++violations;
    EXPECT_EQ(got->axis, want->axis);
    EXPECT_NEAR(got->first_s, want->first_s, 1e-4);
    // The exact extreme is at least the grid's and at most a grid step's curvature away.
    EXPECT_GE(std::abs(got->value - got->limit), std::abs(want->value - want->limit) - 1e-9);
    EXPECT_NEAR(got->value, want->value, 1e-3);
  }
  EXPECT_GT(violations, 10);  // the random moves exercise both outcomes
  EXPECT_LT(violations, 55);
}

}  // namespace
}  // namespace mdhd::kin

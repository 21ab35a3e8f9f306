// Joint paths: lines, arcs in the three planes, helices, full turns and tcp moves.
#include "sim/kinematics/joint_path.h"

#include <cmath>
#include <numbers>

#include "sim/kinematics/presets.h"
#include "tests/kinematics/expect_vec.h"
#include "tests/kinematics/joint_moves.h"

namespace mdhd::kin {
namespace {

constexpr double kJointTol = 1e-9;
const double kH = std::sqrt(0.5);

gcode::Motion line(JointValues a, JointValues b) {
  gcode::Motion m;
  m.type = gcode::MotionType::kFeed;
  m.start = a;
  m.end = b;
  return m;
}

gcode::Motion arc(gcode::Plane plane, JointValues a, JointValues b, double c0, double c1,
                  int turn) {
  gcode::Motion m = line(a, b);
  m.type = gcode::MotionType::kArc;
  m.plane = plane;
  m.center = {c0, c1};
  m.turn = turn;
  return m;
}

using test_support::xyz;

glm::dvec3 pos(const JointValues& q) {
  return {q[0], q[1], q[2]};
}

TEST(JointPath, LineIsLinearInJointSpace) {
  const Kinematics kin(presets::acTrunnion());
  JointValues b = xyz(10, 20, -5);
  b[gcode::kA] = 30;
  b[gcode::kC] = -90;
  const JointPath p(kin, line({}, b), 50);
  const JointValues q = p.at(0.25);
  EXPECT_VEC_NEAR(pos(q), glm::dvec3(2.5, 5, -1.25), kJointTol);
  EXPECT_DOUBLE_EQ(q[gcode::kA], 7.5);
  EXPECT_DOUBLE_EQ(q[gcode::kC], -22.5);
  EXPECT_EQ(p.at(0), JointValues{});
  EXPECT_EQ(p.at(1), b);
  EXPECT_EQ(p.at(-3), JointValues{});  // clamped
  EXPECT_EQ(p.at(7), b);
  EXPECT_FALSE(p.isArc());
}

TEST(JointPath, ArcXyCounterClockwiseQuarter) {
  const Kinematics kin(presets::threeAxisMill());
  // G17 G3 from (10, 0) to (0, 10) about the origin: a quarter turn through 45 degrees.
  const JointPath p(kin, arc(gcode::Plane::kXY, xyz(10, 0, 0), xyz(0, 10, 0), 0, 0, 1), 0);
  EXPECT_NEAR(p.arcSweep(), std::numbers::pi / 2, 1e-15);
  EXPECT_VEC_NEAR(pos(p.at(0.5)), glm::dvec3(10 * kH, 10 * kH, 0), kJointTol);
}

TEST(JointPath, ArcXyClockwiseTakesTheLongWay) {
  const Kinematics kin(presets::threeAxisMill());
  // G2 from (10, 0) to (0, 10): three quarters clockwise, through (0, -10) and (-10, 0).
  const JointPath p(kin, arc(gcode::Plane::kXY, xyz(10, 0, 0), xyz(0, 10, 0), 0, 0, -1), 0);
  EXPECT_NEAR(p.arcSweep(), -1.5 * std::numbers::pi, 1e-15);
  EXPECT_VEC_NEAR(pos(p.at(1.0 / 3)), glm::dvec3(0, -10, 0), kJointTol);
  EXPECT_VEC_NEAR(pos(p.at(2.0 / 3)), glm::dvec3(-10, 0, 0), kJointTol);
}

TEST(JointPath, ArcXzRotatesAboutPlusY) {
  const Kinematics kin(presets::threeAxisMill());
  // G18 G3: ccw about +Y takes +X to -Z (R_y(90) (10, 0, 0) = (0, 0, -10)). Centre is (Z, X).
  const JointPath p(kin, arc(gcode::Plane::kXZ, xyz(10, 5, 0), xyz(0, 5, -10), 0, 0, 1), 0);
  EXPECT_VEC_NEAR(pos(p.at(0.5)), glm::dvec3(10 * kH, 5, -10 * kH), kJointTol);
  EXPECT_EQ(p.arcFirst(), gcode::kZ);
  EXPECT_EQ(p.arcSecond(), gcode::kX);
}

TEST(JointPath, ArcYzRotatesAboutPlusX) {
  const Kinematics kin(presets::threeAxisMill());
  // G19 G3: ccw about +X takes +Y to +Z. Centre (Y, Z) = (0, 0), X is the helix axis here.
  const JointPath p(kin, arc(gcode::Plane::kYZ, xyz(0, 10, 0), xyz(4, 0, 10), 0, 0, 1), 0);
  EXPECT_VEC_NEAR(pos(p.at(0.5)), glm::dvec3(2, 10 * kH, 10 * kH), kJointTol);
}

TEST(JointPath, HelixFullTurnsAndOtherJointsLinear) {
  const Kinematics kin(presets::bcHeadTable());
  // Full circle (start == end in the plane), two turns (P2), descending 4 mm, C 0 -> 90.
  JointValues a = xyz(30, 20, 0);
  JointValues b = xyz(30, 20, -4);
  b[gcode::kC] = 90;
  const JointPath p(kin, arc(gcode::Plane::kXY, a, b, 20, 20, 2), 0);
  EXPECT_NEAR(p.arcSweep(), 4 * std::numbers::pi, 1e-12);
  // s = 1/4: one half turn done: (10, 20), Z -1, C 22.5.
  JointValues q = p.at(0.25);
  EXPECT_VEC_NEAR(pos(q), glm::dvec3(10, 20, -1), kJointTol);
  EXPECT_DOUBLE_EQ(q[gcode::kC], 22.5);
  q = p.at(0.5);
  EXPECT_VEC_NEAR(pos(q), glm::dvec3(30, 20, -2), kJointTol);
  // Clockwise full circle.
  const JointPath cw(kin, arc(gcode::Plane::kXY, a, a, 20, 20, -1), 0);
  EXPECT_NEAR(cw.arcSweep(), -2 * std::numbers::pi, 1e-12);
  EXPECT_VEC_NEAR(pos(cw.at(0.25)), glm::dvec3(20, 10, 0), kJointTol);
}

TEST(JointPath, ArcRadiusBlendsWhenEndsDiffer) {
  const Kinematics kin(presets::threeAxisMill());
  // The interpreter allows a small radius mismatch; the path spirals from 10 to 10.002.
  const JointPath p(kin, arc(gcode::Plane::kXY, xyz(10, 0, 0), xyz(0, 10.002, 0), 0, 0, 1), 0);
  EXPECT_VEC_NEAR(pos(p.at(0.5)), glm::dvec3(10.001 * kH, 10.001 * kH, 0), kJointTol);
  EXPECT_EQ(pos(p.at(1)), glm::dvec3(0, 10.002, 0));
}

TEST(JointPath, ArcWithTurnZeroIsAnError) {
  const Kinematics kin(presets::threeAxisMill());
  gcode::Motion m = arc(gcode::Plane::kXY, xyz(10, 0, 0), xyz(0, 10, 0), 0, 0, 0);
  m.pos.line = 12;
  try {
    JointPath p(kin, m, 0);
    FAIL();
  } catch (const KinematicsError& e) {
    EXPECT_STREQ(e.what(), "line 12: arc with turn 0");
  }
}

TEST(JointPath, NonFiniteInputIsAnError) {
  const Kinematics kin(presets::threeAxisMill());
  gcode::Motion m = line(xyz(0, 0, 0), xyz(1, std::nan(""), 0));
  m.pos.line = 4;
  try {
    JointPath p(kin, m, 0);
    FAIL();
  } catch (const KinematicsError& e) {
    EXPECT_STREQ(e.what(), "line 4: non-finite value of axis Y");
  }
  m.end = xyz(1, 1, 1);
  EXPECT_THROW(JointPath(kin, m, INFINITY), KinematicsError);
  m = arc(gcode::Plane::kXY, xyz(10, 0, 0), xyz(0, 10, 0), 0, INFINITY, 1);
  EXPECT_THROW(JointPath(kin, m, 0), KinematicsError);
}

TEST(JointPath, TcpTipStaysOnTheStraightLine) {
  const Kinematics kin(presets::acTrunnion());
  // G43.4: tip from (0, 0, 10) to (20, 10, 10) in W while A goes 0 -> -60 and C 0 -> 90.
  JointValues a = xyz(0, 0, 10);
  JointValues b = xyz(20, 10, 10);
  b[gcode::kA] = -60;
  b[gcode::kC] = 90;
  gcode::Motion m = line(a, b);
  m.tcp = true;
  const double length = 50;
  const JointPath p(kin, m, length);
  EXPECT_TRUE(p.tcp());
  for (int i = 0; i <= 64; ++i) {
    const double s = i / 64.0;
    const JointValues q = p.at(s);
    SCOPED_TRACE(s);
    EXPECT_VEC_NEAR(kin.toolPose(q, length).tip, glm::mix(pos(a), pos(b), s), 1e-9);
    EXPECT_NEAR(q[gcode::kA], -60 * s, 1e-12);
    EXPECT_NEAR(q[gcode::kC], 90 * s, 1e-12);
  }
  // The joints really move off the program line: at A-60 C90 the Z joint is not 60.
  EXPECT_GT(std::abs(p.endJoints()[gcode::kZ] - 60), 1.0);
  EXPECT_VEC_NEAR(kin.toolPose(p.endJoints(), length).tip, pos(b), 1e-9);
}

TEST(JointPath, TcpOnAHeadMachine) {
  const Kinematics kin(presets::nutatingB45());
  JointValues a = xyz(-10, 5, 0);
  JointValues b = xyz(30, -5, 2);
  b[gcode::kB] = 150;
  b[gcode::kC] = -45;
  gcode::Motion m = line(a, b);
  m.tcp = true;
  const JointPath p(kin, m, 35);
  for (int i = 0; i <= 20; ++i) {
    const double s = i / 20.0;
    EXPECT_VEC_NEAR(kin.toolPose(p.at(s), 35).tip, glm::mix(pos(a), pos(b), s), 1e-9);
  }
}

TEST(JointPath, TcpArcKeepsTheTipOnTheCircle) {
  const Kinematics kin(presets::bcHeadTable());
  JointValues a = xyz(10, 0, 5);
  JointValues b = xyz(-10, 0, 5);
  b[gcode::kB] = 45;
  gcode::Motion m = arc(gcode::Plane::kXY, a, b, 0, 0, 1);
  m.tcp = true;
  const JointPath p(kin, m, 40);
  // Half circle ccw through (0, 10): the tip at s = 0.5 with B 22.5.
  const JointValues q = p.at(0.5);
  EXPECT_VEC_NEAR(kin.toolPose(q, 40).tip, glm::dvec3(0, 10, 5), 1e-9);
  EXPECT_DOUBLE_EQ(q[gcode::kB], 22.5);
  EXPECT_VEC_NEAR(pos(p.programAt(0.5)), glm::dvec3(0, 10, 5), 1e-12);
}

TEST(JointPath, TcpOnASingularMachineIsAnError) {
  Machine mach = presets::threeAxisMill();
  mach.joints[1].axis = {1, 0, 0};
  const Kinematics kin(mach);
  gcode::Motion m = line(xyz(0, 0, 0), xyz(1, 1, 1));
  m.tcp = true;
  m.pos.line = 3;
  EXPECT_THROW(JointPath(kin, m, 10), KinematicsError);
}

}  // namespace
}  // namespace mdhd::kin

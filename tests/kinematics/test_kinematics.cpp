// Forward kinematics: hand-worked poses of every preset and the example jobs' poses.
#include "sim/kinematics/kinematics.h"

#include <cmath>
#include <numbers>

#include "sim/kinematics/presets.h"
#include "tests/kinematics/expect_vec.h"

namespace mdhd::kin {
namespace {

constexpr double kTol = 1e-9;

JointValues joints(std::initializer_list<std::pair<gcode::Axis, double>> values) {
  JointValues q{};
  for (const auto& [a, v] : values) q[a] = v;
  return q;
}

double sinDeg(double d) {
  return std::sin(d * std::numbers::pi / 180.0);
}
double cosDeg(double d) {
  return std::cos(d * std::numbers::pi / 180.0);
}

TEST(SinCosDegrees, ExactAtQuarterTurnsAndPeriodic) {
  double s = 0, c = 0;
  sinCosDegrees(-90, s, c);
  EXPECT_EQ(s, -1.0);
  EXPECT_EQ(c, 0.0);
  sinCosDegrees(540, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, -1.0);
  sinCosDegrees(-330, s, c);
  EXPECT_NEAR(s, 0.5, 1e-15);
  EXPECT_NEAR(c, std::sqrt(3.0) / 2, 1e-15);
  sinCosDegrees(1e6 + 25, s, c);  // 1e6 = 2777 turns + 280 degrees
  EXPECT_NEAR(s, sinDeg(305), 1e-12);
  EXPECT_NEAR(c, cosDeg(305), 1e-12);
}

TEST(Kinematics, ThreeAxisTipIsGaugeMinusLength) {
  const Kinematics kin(presets::threeAxisMill());
  // Gauge point = (X, Y, Z); the tip is 50 below it.
  const ToolPose p = kin.toolPose(joints({{gcode::kX, 10}, {gcode::kY, 20}, {gcode::kZ, 30}}), 50);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(10, 20, -20), kTol);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(0, 0, 1), kTol);
  EXPECT_EQ(axisLetterString(kin.machine()), "XYZ");
  EXPECT_FALSE(kin.hasAxis(gcode::kA));
}

TEST(Kinematics, AcTrunnionSideDrillExample) {
  // README: A-90 C0, G43 with length 60, programmed X0 Y15 Z5 -> Z joint 65.
  // W = R_x(-90); gauge in W = R_x(90) (0, 15, 65) = (0, -65, 15); axis R_x(90) z = -y;
  // tip = gauge - 60 axis = (0, -5, 15).
  const Kinematics kin(presets::acTrunnion());
  const ToolPose p = kin.toolPose(joints({{gcode::kY, 15}, {gcode::kZ, 65}, {gcode::kA, -90}}), 60);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(0, -5, 15), kTol);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(0, -1, 0), kTol);
}

TEST(Kinematics, AcTrunnionCTurnsTheTableUnderTheTool) {
  const Kinematics kin(presets::acTrunnion());
  // C90: W = R_z(90), so machine (10, 0, 50) is R_z(-90) (10, 0, 50) = (0, -10, 50) in W.
  ToolPose p = kin.toolPose(joints({{gcode::kX, 10}, {gcode::kZ, 50}, {gcode::kC, 90}}), 50);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(0, -10, 0), kTol);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(0, 0, 1), kTol);
  // A-90 C90: W = R_x(-90) R_z(90); gauge R_z(-90) R_x(90) (0, 15, 65) = R_z(-90) (0, -65, 15)
  // = (-65, 0, 15); axis R_z(-90) (0, -1, 0) = (-1, 0, 0); tip = (-5, 0, 15).
  p = kin.toolPose(joints({{gcode::kY, 15}, {gcode::kZ, 65}, {gcode::kA, -90}, {gcode::kC, 90}}),
                   60);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(-5, 0, 15), kTol);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(-1, 0, 0), kTol);
}

TEST(Kinematics, BcTrunnionRotatesAboutAnOffsetAxis) {
  // B axis through o = (0, 0, -50). B90: W -> machine is T(o) R_y(90) T(-o); its inverse
  // takes the gauge (0, 0, 100): p - o = (0, 0, 150), R_y(-90) -> (-150, 0, 0), + o ->
  // (-150, 0, -50). Axis R_y(-90) z = (-1, 0, 0); tip with length 100 = (-50, 0, -50).
  const Kinematics kin(presets::bcTrunnion());
  const ToolPose p = kin.toolPose(joints({{gcode::kZ, 100}, {gcode::kB, 90}}), 100);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(-50, 0, -50), kTol);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(-1, 0, 0), kTol);
  // All joints zero: W is the machine frame.
  EXPECT_VEC_NEAR(kin.toolPose(JointValues{}, 10).tip, glm::dvec3(0, 0, -10), kTol);
}

TEST(Kinematics, BcHeadTablePivotAndTable) {
  const Kinematics kin(presets::bcHeadTable());
  // Pivot o = (0, 0, 100). B90: gauge = o - R_y(90) o = (-100, 0, 100), axis R_y(90) z = +x,
  // tip (length 50) = (-150, 0, 100). X10 Y20 Z30 add (10, 20, 30): tip (-140, 20, 130).
  // C90: W = R_z(90), W coordinates R_z(-90) (x, y, z) = (y, -x, z): (20, 140, 130),
  // axis (0, -1, 0).
  ToolPose p = kin.toolPose(joints({{gcode::kB, 90}}), 50);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(-150, 0, 100), kTol);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(1, 0, 0), kTol);
  p = kin.toolPose(
      joints({{gcode::kX, 10}, {gcode::kY, 20}, {gcode::kZ, 30}, {gcode::kB, 90}, {gcode::kC, 90}}),
      50);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(20, 140, 130), kTol);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(0, -1, 0), kTol);
}

// The machine of examples/machine-bc-head-table.json: pivot at the gauge point, C about
// the vertical line through (2, 2).
Machine donutMachine() {
  Machine m = presets::bcHeadTable();
  m.joints[3].origin = {0, 0, 0};
  m.joints[4].origin = {2, 2, 0};
  return m;
}

TEST(Kinematics, DonutExamplePose) {
  // README: B-25 C0, machine X-4.76237 Y2 Z18.80096, length 20: axis R_y(-25) z =
  // (-sin 25, 0, cos 25); tip = gauge - 20 axis = (-4.76237 + 8.45237, 2, 18.80096 - 18.12616).
  const Kinematics kin(donutMachine());
  JointValues q =
      joints({{gcode::kX, -4.76237}, {gcode::kY, 2}, {gcode::kZ, 18.80096}, {gcode::kB, -25}});
  ToolPose p = kin.toolPose(q, 20);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(-sinDeg(25), 0, cosDeg(25)), kTol);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(3.69, 2, 0.6748), 1e-5);  // README gives 4-5 digits
  // C90 turns W by +90 about (2, 2): the tip (3.69, 2) relative (1.69, 0) -> R_z(-90) ->
  // (0, -1.69) -> (2, 0.31); the axis leans along +y.
  q[gcode::kC] = 90;
  const ToolPose r = kin.toolPose(q, 20);
  EXPECT_VEC_NEAR(r.tip, glm::dvec3(2, 2 - (p.tip.x - 2), p.tip.z), kTol);
  EXPECT_VEC_NEAR(r.axis, glm::dvec3(0, sinDeg(25), cosDeg(25)), kTol);
}

TEST(Kinematics, AbHeadHeadPoses) {
  const Kinematics kin(presets::abHeadHead());
  // A90: axis R_x(90) z = (0, -1, 0); gauge = o - R_x(90) o = (0, 0, 100) - (0, -100, 0)
  // = (0, 100, 100); tip (length 50) = (0, 150, 100).
  ToolPose p = kin.toolPose(joints({{gcode::kA, 90}}), 50);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(0, -1, 0), kTol);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(0, 150, 100), kTol);
  // B-90: axis R_y(-90) z = (-1, 0, 0); gauge = o - (-100, 0, 0) = (100, 0, 100); tip (150, 0,
  // 100).
  p = kin.toolPose(joints({{gcode::kB, -90}}), 50);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(-1, 0, 0), kTol);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(150, 0, 100), kTol);
  // A90 B90: both pivots coincide, T = T(o) R_x R_y T(-o): axis R_x(90) (1, 0, 0) = (1, 0, 0),
  // gauge = o - R_x R_y o = (0, 0, 100) - (100, 0, 0); tip (-150, 0, 100).
  p = kin.toolPose(joints({{gcode::kA, 90}, {gcode::kB, 90}}), 50);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(1, 0, 0), kTol);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(-150, 0, 100), kTol);
}

TEST(Kinematics, BcHeadHeadCarriesBWithC) {
  const Kinematics kin(presets::bcHeadHead());
  // C90 B90: in C's frame the gauge is (-100, 0, 100) and the axis +x; R_z(90) maps them to
  // (0, -100, 100) and +y; tip (length 50) = (0, -150, 100).
  const ToolPose p = kin.toolPose(joints({{gcode::kB, 90}, {gcode::kC, 90}}), 50);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(0, 1, 0), kTol);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(0, -150, 100), kTol);
  EXPECT_EQ(axisLetterString(kin.machine()), "XYZBC");
}

TEST(Kinematics, NutatingHeadAt45Degrees) {
  const Kinematics kin(presets::nutatingB45());
  const double h = std::sqrt(0.5);
  // u = (0, 1, 1)/sqrt 2. B180: R = 2 u u^T - I, R z = (0, 1, 0), R o = (0, 100, 0):
  // gauge = (0, -100, 100), tip (length 50) = (0, -150, 100): a horizontal spindle.
  ToolPose p = kin.toolPose(joints({{gcode::kB, 180}}), 50);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(0, 1, 0), kTol);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(0, -150, 100), kTol);
  // B90: R z = u x z + u (u.z) = (h, 0, 0) + (0, .5, .5): 60 degrees from vertical.
  // gauge = o - 100 R z = (-100 h, -50, 50); tip = gauge - 50 R z = (-150 h, -75, 25).
  p = kin.toolPose(joints({{gcode::kB, 90}}), 50);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(h, 0.5, 0.5), kTol);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(-150 * h, -75, 25), kTol);
}

TEST(Kinematics, ToolInWorkpieceCarriesTheWholeTool) {
  const Kinematics kin(presets::bcHeadTable());
  const JointValues q = joints({{gcode::kX, 5}, {gcode::kB, 30}, {gcode::kC, -40}});
  const Rigid t = kin.toolInWorkpiece(q);
  const ToolPose p = kin.toolPose(q, 42);
  // The tip is the point (0, 0, -42) of the tool frame; the holder 10 above the gauge too.
  EXPECT_VEC_NEAR(t.point({0, 0, -42}), p.tip, kTol);
  EXPECT_VEC_NEAR(t.point({0, 0, 10}), p.tip + 52.0 * p.axis, kTol);
  // Rigid: orthonormal with determinant 1, and the 4x4 agrees.
  EXPECT_NEAR(glm::determinant(t.rotation), 1.0, 1e-12);
  const glm::dvec4 m = t.matrix() * glm::dvec4(0, 0, -42, 1);
  EXPECT_VEC_NEAR(glm::dvec3(m), p.tip, kTol);
}

TEST(Kinematics, InvalidMachineThrowsWithTheField) {
  Machine m = presets::acTrunnion();
  m.workpiece_chain.push_back(0);  // X in both chains
  try {
    Kinematics kin(m);
    FAIL() << "no error";
  } catch (const KinematicsError& e) {
    EXPECT_STREQ(e.what(),
                 "machine.workpiece_chain[2]: joint X is already in the tool_chain; a joint "
                 "belongs to one chain only");
  }
}

}  // namespace
}  // namespace mdhd::kin

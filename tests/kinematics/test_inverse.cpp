// G43.4 solve: FK -> IK -> FK round trips on every preset, and the failure cases.
#include "sim/kinematics/inverse.h"

#include <random>

#include "sim/kinematics/presets.h"
#include "tests/kinematics/expect_vec.h"

namespace mdhd::kin {
namespace {

std::vector<Machine> allPresets() {
  return {presets::threeAxisMill(), presets::acTrunnion(), presets::bcTrunnion(),
          presets::bcHeadTable(),   presets::abHeadHead(), presets::bcHeadHead(),
          presets::nutatingB45()};
}

TEST(SolveTip, SideDrillExample) {
  // The side drill as G43.4 would program it: the tip (0, -5, 15) in W at A-90 needs
  // X0 Y15 Z65 with a 60 mm tool.
  const Kinematics kin(presets::acTrunnion());
  JointValues q{};
  q[gcode::kA] = -90;
  ASSERT_TRUE(solveTip(kin, {0, -5, 15}, 60, q));
  EXPECT_NEAR(q[gcode::kX], 0, 1e-12);
  EXPECT_NEAR(q[gcode::kY], 15, 1e-12);
  EXPECT_NEAR(q[gcode::kZ], 65, 1e-12);
  EXPECT_EQ(q[gcode::kA], -90);
}

TEST(SolveTip, RoundTripsOnEveryPresetForRandomPoses) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-180, 180);
  std::uniform_real_distribution<double> coord(-300, 300);
  for (const Machine& m : allPresets()) {
    const Kinematics kin(m);
    for (int i = 0; i < 200; ++i) {
      JointValues q{};
      for (int a = gcode::kA; a <= gcode::kC; ++a) {
        if (kin.hasAxis(static_cast<gcode::Axis>(a))) q[a] = angle(rng);
      }
      const double length = 20 + 0.5 * (coord(rng) + 300) / 3;
      const glm::dvec3 tip{coord(rng), coord(rng), coord(rng)};
      JointValues solved = q;
      ASSERT_TRUE(solveTip(kin, tip, length, solved)) << m.name;
      EXPECT_VEC_NEAR(kin.toolPose(solved, length).tip, tip, 1e-9);
      // Only X Y Z moved.
      for (int a = gcode::kA; a < gcode::kAxisCount; ++a) EXPECT_EQ(solved[a], q[a]);
      // FK -> IK gives back the joints.
      JointValues again = solved;
      again[gcode::kX] = again[gcode::kY] = again[gcode::kZ] = 12345;
      ASSERT_TRUE(solveTip(kin, kin.toolPose(solved, length).tip, length, again));
      for (int a = gcode::kX; a <= gcode::kZ; ++a) EXPECT_NEAR(again[a], solved[a], 1e-9);
    }
  }
}

// A moving-table mill: X and Y carry the trunnion (table moves opposite to the joint so
// that +X still moves the tool +X relative to the part), Z carries the spindle.
Machine movingTable() {
  Machine m = presets::acTrunnion();
  m.joints[0].axis = {-1, 0, 0};
  m.joints[1].axis = {0, -1, 0};
  m.tool_chain = {2};
  m.workpiece_chain = {0, 1, 3, 4};
  return m;
}

TEST(SolveTip, JacobianMatchesFiniteDifferences) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const Machine& m : {presets::bcTrunnion(), presets::nutatingB45(), movingTable()}) {
    const Kinematics kin(m);
    for (int i = 0; i < 20; ++i) {
      JointValues q{100 * u(rng),
                    100 * u(rng),
                    100 * u(rng),
                    90 * u(rng),
                    90 * u(rng),
                    180 * u(rng),
                    0,
                    0,
                    0};
      glm::dmat3 jac;
      const glm::dvec3 tip = kin.tipJacobian(q, 40, jac);
      EXPECT_VEC_NEAR(tip, kin.toolPose(q, 40).tip, 1e-12);
      for (int c = 0; c < 3; ++c) {
        JointValues step = q;
        step[static_cast<std::size_t>(c)] += 2.5;
        EXPECT_VEC_NEAR((kin.toolPose(step, 40).tip - tip) / 2.5, jac[c], 1e-12);
      }
    }
  }
}

TEST(SolveTip, MovingTableRoundTrips) {
  const Kinematics kin(movingTable());
  // All zero but X 10: the table moved -10, so the tool sits at x = +10 in W.
  JointValues q{};
  q[gcode::kX] = 10;
  EXPECT_VEC_NEAR(kin.toolPose(q, 0).tip, glm::dvec3(10, 0, 0), 1e-12);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100; ++i) {
    JointValues r{0, 0, 0, 90 * u(rng), 0, 180 * u(rng), 0, 0, 0};
    const glm::dvec3 tip{200 * u(rng), 200 * u(rng), 200 * u(rng)};
    ASSERT_TRUE(solveTip(kin, tip, 55, r));
    EXPECT_VEC_NEAR(kin.toolPose(r, 55).tip, tip, 1e-9);
  }
}

// G43.4 switched on and off at rest (the interpreter's tcp_switch): to the tip and
// back gives the same joints on every preset; rotary joints are never touched.
TEST(SwitchTcp, JointsToTipAndBackOnEveryPreset) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-180, 180), coord(-300, 300);
  for (const Machine& m : allPresets()) {
    const Kinematics kin(m);
    for (int i = 0; i < 50; ++i) {
      JointValues q{};
      for (int a = 0; a < gcode::kAxisCount; ++a)
        if (kin.hasAxis(static_cast<gcode::Axis>(a)))
          q[a] = a <= gcode::kZ ? coord(rng) : angle(rng);
      const double length = 30 + (coord(rng) + 300) / 10;
      const gcode::AxisValues tcp = switchTcp(kin, q, length, true);
      EXPECT_VEC_NEAR(glm::dvec3(tcp[0], tcp[1], tcp[2]), kin.toolPose(q, length).tip, 1e-9);
      const gcode::AxisValues back = switchTcp(kin, tcp, length, false);
      for (int a = 0; a < gcode::kAxisCount; ++a) {
        EXPECT_NEAR(back[a], q[a], 1e-9) << m.name << " axis " << a;
        if (a > gcode::kZ) {
          EXPECT_EQ(tcp[a], q[a]);
        }
      }
    }
  }
}

TEST(SolveTip, SingularMachineIsReported) {
  // Y parallel to X: no joint moves the tip along y.
  Machine m = presets::threeAxisMill();
  m.joints[1].axis = {1, 0, 0};
  const Kinematics kin(m);
  JointValues q{};
  q[gcode::kX] = 7;
  EXPECT_FALSE(solveTip(kin, {1, 2, 3}, 10, q));
  EXPECT_EQ(q[gcode::kX], 7);  // unchanged
  EXPECT_THROW(solveTipOrThrow(kin, {1, 2, 3}, 10, q), KinematicsError);
}

TEST(SolveTip, MachineWithoutZCannotUseTcp) {
  Machine m = presets::threeAxisMill();
  m.joints.pop_back();
  m.tool_chain.pop_back();
  m.home = {};
  const Kinematics kin(m);
  JointValues q{};
  EXPECT_FALSE(solveTip(kin, {1, 2, 3}, 10, q));
  try {
    solveTipOrThrow(kin, {1, 2, 3}, 10, q);
    FAIL();
  } catch (const KinematicsError& e) {
    EXPECT_STREQ(e.what(), "G43.4 needs linear joints X, Y and Z; the machine has XY");
  }
}

}  // namespace
}  // namespace mdhd::kin

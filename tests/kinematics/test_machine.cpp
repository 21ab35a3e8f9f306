// Machine validation: every problem named by its field; axis letters.
#include "sim/kinematics/machine.h"

#include <gtest/gtest.h>

#include "sim/kinematics/kinematics.h"
#include "sim/kinematics/presets.h"

namespace mdhd::kin {
namespace {

std::string issues(const Machine& m) {
  std::string out;
  for (const MachineIssue& i : validateMachine(m)) out += i.field + ": " + i.message + "\n";
  return out;
}

TEST(Machine, EveryPresetIsValidAndBuilds) {
  for (const Machine& m : {presets::threeAxisMill(), presets::acTrunnion(), presets::bcTrunnion(),
                           presets::bcHeadTable(), presets::abHeadHead(), presets::bcHeadHead(),
                           presets::nutatingB45()}) {
    EXPECT_EQ(issues(m), "") << m.name;
    EXPECT_NO_THROW(Kinematics{m});
    EXPECT_FALSE(m.name.empty());
  }
}

TEST(Machine, AxisLetters) {
  EXPECT_EQ(axisOfName("B"), gcode::kB);
  EXPECT_EQ(axisOfName("W"), gcode::kW);
  EXPECT_EQ(axisOfName("x"), std::nullopt);  // names are upper case, as the spec writes them
  EXPECT_EQ(axisOfName("XY"), std::nullopt);
  EXPECT_EQ(axisOfName(""), std::nullopt);
  EXPECT_EQ(axisLetterType(gcode::kC), JointType::kRotary);
  EXPECT_EQ(axisLetterType(gcode::kU), JointType::kLinear);
  const Machine m = presets::acTrunnion();
  EXPECT_EQ(axisLetterString(m), "XYZAC");
  const auto has = axisLetters(m);
  EXPECT_TRUE(has[gcode::kA]);
  EXPECT_FALSE(has[gcode::kB]);
  EXPECT_EQ(axisMask(m), 0b101111u);
  EXPECT_EQ(axisMask(presets::bcHeadHead()), 0b110111u);
  EXPECT_EQ(jointIndex(m, gcode::kC), 4);
  EXPECT_EQ(jointIndex(m, gcode::kB), -1);
}

TEST(Machine, JointProblems) {
  Machine m = presets::acTrunnion();
  m.joints[0].axis = {0, 0, 0};
  m.joints[1].name = "Q";
  m.joints[2].limits = Limits{10, -10};
  m.joints[3].type = JointType::kLinear;
  m.joints[4].origin.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(issues(m),
            "joints[0].axis: must be a finite, non-zero direction\n"
            "joints[1].name: \"Q\" is not an axis letter (X Y Z A B C U V W)\n"
            "joints[2].limits: min 10 is above max -10\n"
            "joints[3].type: joint A must be rotary (A B C are rotary axes)\n"
            "joints[4].origin: must be finite\n");
}

TEST(Machine, DuplicateNames) {
  Machine m = presets::acTrunnion();
  m.joints[4].name = "A";
  EXPECT_EQ(issues(m), "joints[4].name: duplicate joint name A (also joints[3])\n");
}

TEST(Machine, ChainProblems) {
  Machine m = presets::acTrunnion();
  m.tool_chain = {0, 1, 1, 7};
  m.workpiece_chain = {3, 0};
  EXPECT_EQ(issues(m),
            "tool_chain[2]: joint Y appears twice in the chain\n"
            "tool_chain[3]: no joint with index 7\n"
            "workpiece_chain[1]: joint X is already in the tool_chain; a joint belongs to "
            "one chain only\n"
            "joints[2]: joint Z is in neither tool_chain nor workpiece_chain\n"
            "joints[4]: joint C is in neither tool_chain nor workpiece_chain\n");
}

TEST(Machine, HomeSpindleAndFeeds) {
  Machine m = presets::threeAxisMill();
  m.home[gcode::kB] = 10;
  m.spindle_axis = {0, 0, 0};
  m.rapid_feed = 0;
  m.max_feed = -5;
  EXPECT_EQ(issues(m),
            "home.B: the machine has no joint of that name\n"
            "spindle_axis: must be a finite, non-zero direction\n"
            "rapid_feed: must be a positive number (mm/min)\n"
            "max_feed: must be a positive number (mm/min)\n");
  m = Machine{};
  m.rapid_feed = m.max_feed = 1;
  EXPECT_EQ(issues(m), "joints: a machine needs at least one joint\n");
}

TEST(Machine, NonUnitAxesAreNormalised) {
  Machine m = presets::threeAxisMill();
  m.joints[0].axis = {2, 0, 0};
  m.spindle_axis = {0, 0, 5};
  const Kinematics kin(m);
  JointValues q{};
  q[gcode::kX] = 3;
  const ToolPose p = kin.toolPose(q, 10);
  EXPECT_EQ(p.tip, glm::dvec3(3, 0, -10));
  EXPECT_EQ(p.axis, glm::dvec3(0, 0, 1));
}

// Any finite non-zero vector is a direction. glm::normalize squared it first: A's axis
// [1e200, 0, 0] became zero (A-90 then turned nothing and G43.4 called every pose
// singular), and [0, 0, 1e-200] was refused as a zero direction.
TEST(Machine, AxesOfAnyFiniteLengthAreDirections) {
  Machine m = presets::acTrunnion();
  m.joints[3].axis = {1e200, 0, 0};
  m.joints[4].axis = {0, 0, 1e-200};
  m.spindle_axis = {0, 1e300, 1e300};
  ASSERT_EQ(issues(m), "");
  const Kinematics kin(m);
  JointValues q{};
  q[gcode::kZ] = 100;
  q[gcode::kA] = -90;
  q[gcode::kC] = 90;
  // Gauge (0, 0, 100), axis (0, 1, 1)/sqrt2 in the machine; W = R_x(-90) R_z(90), so in W
  // p -> R_z(-90) R_x(90) p: (0, 0, 100) -> (0, -100, 0) -> (-100, 0, 0), and the axis
  // (0, 1, 1)/sqrt2 -> (0, -1, 1)/sqrt2 -> (-1, 0, 1)/sqrt2.
  const ToolPose p = kin.toolPose(q, 10 * std::sqrt(2.0));
  const double h = std::sqrt(0.5);
  EXPECT_NEAR(p.axis.x, -h, 1e-12);
  EXPECT_NEAR(p.axis.y, 0, 1e-12);
  EXPECT_NEAR(p.axis.z, h, 1e-12);
  EXPECT_NEAR(p.tip.x, -90, 1e-9);
  EXPECT_NEAR(p.tip.y, 0, 1e-9);
  EXPECT_NEAR(p.tip.z, -10, 1e-9);
  EXPECT_EQ(unitDirection({0x3p-1030, 0, 0x4p-1030}), glm::dvec3(0.6, 0, 0.8));  // subnormal
  EXPECT_EQ(unitDirection({0, 0, 0}), glm::dvec3(0.0));
  EXPECT_EQ(unitDirection({1, std::nan(""), 0}), glm::dvec3(0.0));
}

}  // namespace
}  // namespace mdhd::kin

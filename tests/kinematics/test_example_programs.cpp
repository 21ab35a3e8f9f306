// The example programs of ../shared/examples run through the interpreter, their motions
// through JointPath: the tool poses the examples' README states.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "sim/gcode/interpreter.h"
#include "sim/kinematics/joint_path.h"
#include "sim/kinematics/presets.h"
#include "tests/kinematics/expect_vec.h"

namespace mdhd::kin {
namespace {

struct Collect : gcode::MotionSink {
  std::vector<gcode::Motion> motions;
  void motion(const gcode::Motion& m) override {
    motions.push_back(m);
    motions.back().block_text = nullptr;  // valid during the callback only
  }
};

std::vector<gcode::Motion> runText(const Machine& machine, const std::string& text, int tool,
                                   double length) {
  gcode::InterpreterConfig config;
  config.home = machine.home;
  config.tools.add({tool, length, 0.0});
  config.axis_mask = axisMask(machine);
  Collect sink;
  gcode::Interpreter interp(config, sink);
  interp.run(gcode::makeStringSource(text));
  return sink.motions;
}

std::vector<gcode::Motion> run(const Machine& machine, const char* program, int tool,
                               double length) {
  std::ifstream in(std::string(MDHD_SHARED_DIR) + "/examples/" + program);
  EXPECT_TRUE(in) << program;
  std::stringstream text;
  text << in.rdbuf();
  return runText(machine, text.str(), tool, length);
}

const gcode::Motion& onLine(const std::vector<gcode::Motion>& motions, int line) {
  for (const gcode::Motion& m : motions) {
    if (m.pos.line == line) return m;
  }
  ADD_FAILURE() << "no motion on line " << line;
  return motions.front();
}

// examples/machine-bc-head-table.json
Machine donutExampleMachine() {
  Machine m = presets::bcHeadTable();
  m.joints[3].origin = {0, 0, 0};
  m.joints[4].origin = {2, 2, 0};
  m.home = {-30, 2, 40, 0, 0, 0, 0, 0, 0};
  return m;
}

TEST(ExamplePrograms, DonutTipCirclesTheCAxis) {
  const Kinematics kin(donutExampleMachine());
  const auto motions = run(kin.machine(), "donut-bc.ngc", 1, 20);
  // Line 11: the plunge ends at the README's pose.
  const JointPath plunge(kin, onLine(motions, 11), 20);
  const ToolPose p = kin.toolPose(plunge.endJoints(), 20);
  EXPECT_VEC_NEAR(p.tip, glm::dvec3(3.69, 2, 0.6748), 1e-5);
  const double s25 = std::sin(25 * std::numbers::pi / 180);
  EXPECT_VEC_NEAR(p.axis, glm::dvec3(-s25, 0, std::cos(25 * std::numbers::pi / 180)), 1e-12);
  // The plunge runs 3 mm along the tool axis.
  const ToolPose p0 = kin.toolPose(plunge.startJoints(), 20);
  EXPECT_NEAR(glm::length(p0.tip - p.tip), 3.0, 1e-4);
  EXPECT_NEAR(glm::dot(glm::normalize(p0.tip - p.tip), p.axis), 1.0, 1e-9);
  // Line 12: C0 -> C360, the tip turns about (2, 2) in W at radius 1.69, height fixed, the
  // axis always leaning towards the C axis.
  const JointPath turn(kin, onLine(motions, 12), 20);
  for (int i = 0; i <= 8; ++i) {
    const double s = i / 8.0;
    const ToolPose q = kin.toolPose(turn.at(s), 20);
    const double angle = -2 * std::numbers::pi * s;  // the table turns +C, W by -C
    SCOPED_TRACE(s);
    EXPECT_VEC_NEAR(q.tip,
                    glm::dvec3(2 + (p.tip.x - 2) * std::cos(angle),
                               2 + (p.tip.x - 2) * std::sin(angle), p.tip.z),
                    1e-9);
    EXPECT_NEAR(
        glm::dot(q.axis, glm::normalize(glm::dvec3(2, 2, 0) - glm::dvec3(q.tip.x, q.tip.y, 0))),
        s25, 1e-9);
  }
}

TEST(ExamplePrograms, SideDrillStopsAtYMinus5) {
  Machine m = presets::acTrunnion();
  m.home = {0, 0, 300, 0, 0, 0, 0, 0, 0};
  const Kinematics kin(m);
  const auto motions = run(kin.machine(), "side-drill-ac.ngc", 2, 60);
  const JointPath drill(kin, onLine(motions, 8), 60);  // G1 Z5 F200
  EXPECT_NEAR(drill.endJoints()[gcode::kZ], 65, 1e-12);
  EXPECT_EQ(drill.endJoints()[gcode::kA], -90);
  const ToolPose end = kin.toolPose(drill.endJoints(), 60);
  EXPECT_VEC_NEAR(end.tip, glm::dvec3(0, -5, 15), 1e-9);
  EXPECT_VEC_NEAR(end.axis, glm::dvec3(0, -1, 0), 1e-12);
  // 15 mm deep into the -Y face (y = -20) of the 40 x 40 x 30 stock.
  EXPECT_VEC_NEAR(kin.toolPose(drill.startJoints(), 60).tip, glm::dvec3(0, -25, 15), 1e-9);
}

TEST(ExamplePrograms, ContourArcsStayOnTheirCircles) {
  const Kinematics kin(presets::threeAxisMill());
  const auto motions = run(kin.machine(), "contour-3axis.ngc", 1, 50);
  // G3 corners of radius 5 on lines 9, 11, 13, 15, 2 mm deep.
  const glm::dvec2 centres[] = {{70, 30}, {70, 50}, {30, 50}, {30, 30}};
  const int lines[] = {9, 11, 13, 15};
  for (int k = 0; k < 4; ++k) {
    const JointPath arc(kin, onLine(motions, lines[k]), 50);
    ASSERT_TRUE(arc.isArc());
    EXPECT_NEAR(arc.arcSweep(), std::numbers::pi / 2, 1e-12);
    for (int i = 0; i <= 10; ++i) {
      const ToolPose q = kin.toolPose(arc.at(i / 10.0), 50);
      EXPECT_NEAR(glm::length(glm::dvec2(q.tip) - centres[k]), 5, 1e-9);
      EXPECT_NEAR(q.tip.z, -2, 1e-12);
    }
  }
}

TEST(ExamplePrograms, TcpMoveFromTheInterpreterKeepsTheTipOnItsLine) {
  Machine m = presets::acTrunnion();
  m.home = {0, 0, 300, 0, 0, 0, 0, 0, 0};
  const Kinematics kin(m);
  const auto motions = runText(kin.machine(),
                               "G21 G90 G17 G54\nT1 M6\nG43.4 H1\nG0 X0 Y0 Z10 A0 C0\n"
                               "G1 X20 Y10 Z10 A-60 C90 F500\nG49\nM30\n",
                               1, 50);
  const gcode::Motion& move = onLine(motions, 5);
  ASSERT_TRUE(move.tcp);
  const JointPath path(kin, move, 50);
  for (int i = 0; i <= 16; ++i) {
    const double s = i / 16.0;
    SCOPED_TRACE(s);
    EXPECT_VEC_NEAR(kin.toolPose(path.at(s), 50).tip,
                    glm::mix(glm::dvec3(0, 0, 10), glm::dvec3(20, 10, 10), s), 1e-9);
  }
  EXPECT_EQ(path.endJoints()[gcode::kA], -60);
  EXPECT_EQ(path.endJoints()[gcode::kC], 90);
}

}  // namespace
}  // namespace mdhd::kin

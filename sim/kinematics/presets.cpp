#include "sim/kinematics/presets.h"

#include <cmath>

namespace mdhd::kin::presets {
namespace {

constexpr double kPivot = 100.0;  // head pivot above the gauge point

Joint linear(const char* name, glm::dvec3 axis, double lo, double hi) {
  return {name, JointType::kLinear, axis, glm::dvec3(0.0), Limits{lo, hi}};
}

Joint rotary(const char* name, glm::dvec3 axis, glm::dvec3 origin, std::optional<Limits> l) {
  return {name, JointType::kRotary, axis, origin, l};
}

// X Y Z with travels for a mid-size machining centre; Z leaves room for heads.
Machine base(const char* name) {
  Machine m;
  m.name = name;
  m.joints = {linear("X", {1, 0, 0}, -400, 400), linear("Y", {0, 1, 0}, -300, 300),
              linear("Z", {0, 0, 1}, -200, 400)};
  m.tool_chain = {0, 1, 2};
  m.home[gcode::kZ] = 300;
  m.spindle_axis = {0, 0, 1};
  m.rapid_feed = 20000;
  m.max_feed = 10000;
  return m;
}

}  // namespace

Machine threeAxisMill() {
  Machine m = base("3-axis vertical mill");
  return m;
}

Machine acTrunnion() {
  Machine m = base("AC trunnion (table-table)");
  m.joints.push_back(rotary("A", {1, 0, 0}, {0, 0, 0}, Limits{-120, 30}));
  m.joints.push_back(rotary("C", {0, 0, 1}, {0, 0, 0}, std::nullopt));
  m.workpiece_chain = {3, 4};
  return m;
}

Machine bcTrunnion() {
  Machine m = base("BC trunnion (table-table)");
  m.joints.push_back(rotary("B", {0, 1, 0}, {0, 0, -50}, Limits{-110, 110}));
  m.joints.push_back(rotary("C", {0, 0, 1}, {0, 0, 0}, std::nullopt));
  m.workpiece_chain = {3, 4};
  return m;
}

Machine bcHeadTable() {
  Machine m = base("BC head-table (B swivel head, C table)");
  m.joints.push_back(rotary("B", {0, 1, 0}, {0, 0, kPivot}, Limits{-110, 110}));
  m.joints.push_back(rotary("C", {0, 0, 1}, {0, 0, 0}, std::nullopt));
  m.tool_chain = {0, 1, 2, 3};
  m.workpiece_chain = {4};
  return m;
}

Machine abHeadHead() {
  Machine m = base("AB head-head");
  m.joints.push_back(rotary("A", {1, 0, 0}, {0, 0, kPivot}, Limits{-95, 95}));
  m.joints.push_back(rotary("B", {0, 1, 0}, {0, 0, kPivot}, Limits{-95, 95}));
  m.tool_chain = {0, 1, 2, 3, 4};
  return m;
}

Machine bcHeadHead() {
  Machine m = base("BC head-head (fork head)");
  m.joints.push_back(rotary("B", {0, 1, 0}, {0, 0, kPivot}, Limits{-120, 120}));
  m.joints.push_back(rotary("C", {0, 0, 1}, {0, 0, 0}, Limits{-360, 360}));
  m.tool_chain = {0, 1, 2, 4, 3};  // C is the outer axis, B sits in the fork
  return m;
}

Machine nutatingB45() {
  Machine m = base("nutating B head at 45 degrees, C table");
  const double h = std::sqrt(0.5);
  m.joints.push_back(rotary("B", {0, h, h}, {0, 0, kPivot}, Limits{0, 180}));
  m.joints.push_back(rotary("C", {0, 0, 1}, {0, 0, 0}, std::nullopt));
  m.tool_chain = {0, 1, 2, 3};
  m.workpiece_chain = {4};
  return m;
}

}  // namespace mdhd::kin::presets

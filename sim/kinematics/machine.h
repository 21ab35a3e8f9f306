#pragma once
// The machine model of the job format (spec section 2): named joints and two
// serial chains from the machine base, one to the spindle and one to the table.
// Plain data; `validateMachine` says what is wrong with it, field by field.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/gcode/motion.h"

namespace mdhd::kin {

using JointValues = gcode::AxisValues;  // indexed by gcode::Axis (the joint's letter)

enum class JointType { kLinear, kRotary };

struct Limits {
  double min = 0.0;
  double max = 0.0;
};

struct Joint {
  std::string name;  // one of the program's axis letters: X Y Z U V W linear, A B C rotary
  JointType type = JointType::kLinear;
  glm::dvec3 axis{0.0, 0.0, 1.0};  // in the parent's frame; normalised when compiled
  // Rotary: a point of the rotation axis. Linear: a fixed offset of the joint's frame
  // (an extension of the spec, zero by default, where the spec's formula holds).
  glm::dvec3 origin{0.0};
  std::optional<Limits> limits;  // absent: no limit (a rotary turns freely)
};

struct Machine {
  std::string name;
  std::vector<Joint> joints;
  std::vector<int> tool_chain;             // indices into joints, base to spindle
  std::vector<int> workpiece_chain;        // indices into joints, base to table
  JointValues home{};                      // by axis letter; joints the machine lacks stay 0
  glm::dvec3 spindle_axis{0.0, 0.0, 1.0};  // in the tool frame, from the tip to the spindle
  double rapid_feed = 0.0;                 // mm/min
  double max_feed = 0.0;                   // mm/min
};

// One problem of a machine: `field` is the path below the machine object in the
// job's JSON spelling ("joints[3].axis", "tool_chain[1]"), `message` says what is wrong.
struct MachineIssue {
  std::string field;
  std::string message;
};

// The unit vector along `v`, or zero when v is zero or not finite. Scaled by its
// largest component first, so any finite non-zero direction works: glm::normalize
// overflows to a zero axis for [1e200, 0, 0] (and gave a degenerate machine).
glm::dvec3 unitDirection(const glm::dvec3& v);

// Every problem found, in field order; empty when the machine can be used.
std::vector<MachineIssue> validateMachine(const Machine& machine);

// The axis letter of a joint name ("X" -> kX), or nullopt when it is not one.
std::optional<gcode::Axis> axisOfName(const std::string& name);

// Whether the letter names a linear (X Y Z U V W) or a rotary (A B C) axis.
JointType axisLetterType(gcode::Axis axis);

// Index into machine.joints of the joint named by the letter, or -1.
int jointIndex(const Machine& machine, gcode::Axis axis);

// Which program axis letters the machine has (the interpreter rejects the others).
std::array<bool, gcode::kAxisCount> axisLetters(const Machine& machine);

// The same as a bit mask, bit i for gcode::kAxisLetters[i] (InterpreterConfig::axis_mask).
unsigned axisMask(const Machine& machine);

// The same as a string in canonical order, e.g. "XYZBC".
std::string axisLetterString(const Machine& machine);

}  // namespace mdhd::kin

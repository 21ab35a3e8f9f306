#include "sim/kinematics/machine.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

namespace mdhd::kin {
namespace {

// A limit as the user wrote it ("-120", "30.5"), not std::to_string's "-120.000000".
std::string shortText(double v) {
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string indexed(const std::string& field, std::size_t i) {
  return field + "[" + std::to_string(i) + "]";
}

void checkJoint(const Joint& joint, const std::string& field, std::vector<MachineIssue>& issues) {
  const auto letter = axisOfName(joint.name);
  if (!letter) {
    issues.push_back(
        {field + ".name", "\"" + joint.name + "\" is not an axis letter (X Y Z A B C U V W)"});
  } else if (axisLetterType(*letter) != joint.type) {
    issues.push_back({field + ".type", "joint " + joint.name + " must be " +
                                           (axisLetterType(*letter) == JointType::kLinear
                                                ? "linear (X Y Z U V W are linear axes)"
                                                : "rotary (A B C are rotary axes)")});
  }
  if (unitDirection(joint.axis) == glm::dvec3(0.0)) {
    issues.push_back({field + ".axis", "must be a finite, non-zero direction"});
  }
  if (!finite(joint.origin)) issues.push_back({field + ".origin", "must be finite"});
  if (joint.limits) {
    const Limits& l = *joint.limits;
    if (!std::isfinite(l.min) || !std::isfinite(l.max)) {
      issues.push_back({field + ".limits", "must be finite"});
    } else if (l.min > l.max) {
      issues.push_back(
          {field + ".limits", "min " + shortText(l.min) + " is above max " + shortText(l.max)});
    }
  }
}

// Each joint index valid and used once, in one chain only. `seen` is the chain
// (0 none, 1 tool, 2 workpiece) that already holds each joint.
void checkChain(const Machine& m, const std::vector<int>& chain, const std::string& field,
                int chainId, std::vector<int>& seen, std::vector<MachineIssue>& issues) {
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const int j = chain[i];
    if (j < 0 || j >= static_cast<int>(m.joints.size())) {
      issues.push_back({indexed(field, i), "no joint with index " + std::to_string(j)});
      continue;
    }
    const std::string& name = m.joints[static_cast<std::size_t>(j)].name;
    int& owner = seen[static_cast<std::size_t>(j)];
    if (owner == chainId) {
      issues.push_back({indexed(field, i), "joint " + name + " appears twice in the chain"});
    } else if (owner != 0) {
      issues.push_back({indexed(field, i), "joint " + name +
                                               " is already in the tool_chain; a joint "
                                               "belongs to one chain only"});
    }
    owner = chainId;
  }
}

}  // namespace

glm::dvec3 unitDirection(const glm::dvec3& v) {
  if (!finite(v)) return glm::dvec3(0.0);
  const double big = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(big > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 w = v / big;  // largest component +-1: no overflow, no underflow to 0
  return w / std::sqrt(glm::dot(w, w));
}

std::optional<gcode::Axis> axisOfName(const std::string& name) {
  if (name.size() != 1) return std::nullopt;
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    if (gcode::kAxisLetters[a] == name[0]) return static_cast<gcode::Axis>(a);
  }
  return std::nullopt;
}

JointType axisLetterType(gcode::Axis axis) {
  return (axis == gcode::kA || axis == gcode::kB || axis == gcode::kC) ? JointType::kRotary
                                                                       : JointType::kLinear;
}

int jointIndex(const Machine& machine, gcode::Axis axis) {
  for (std::size_t i = 0; i < machine.joints.size(); ++i) {
    if (axisOfName(machine.joints[i].name) == axis) return static_cast<int>(i);
  }
  return -1;
}

std::array<bool, gcode::kAxisCount> axisLetters(const Machine& machine) {
  std::array<bool, gcode::kAxisCount> has{};
  for (const Joint& j : machine.joints) {
    if (const auto a = axisOfName(j.name)) has[*a] = true;
  }
  return has;
}

unsigned axisMask(const Machine& machine) {
  const auto has = axisLetters(machine);
  unsigned mask = 0;
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    if (has[static_cast<std::size_t>(a)]) mask |= 1u << a;
  }
  return mask;
}

std::string axisLetterString(const Machine& machine) {
  const auto has = axisLetters(machine);
  std::string s;
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    if (has[static_cast<std::size_t>(a)]) s += gcode::kAxisLetters[a];
  }
  return s;
}

std::vector<MachineIssue> validateMachine(const Machine& m) {
  std::vector<MachineIssue> issues;
  if (m.joints.empty()) issues.push_back({"joints", "a machine needs at least one joint"});
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    checkJoint(m.joints[i], indexed("joints", i), issues);
    for (std::size_t k = 0; k < i; ++k) {
      if (m.joints[k].name == m.joints[i].name) {
        issues.push_back({indexed("joints", i) + ".name", "duplicate joint name " +
                                                              m.joints[i].name + " (also joints[" +
                                                              std::to_string(k) + "])"});
        break;
      }
    }
  }
  std::vector<int> seen(m.joints.size(), 0);
  checkChain(m, m.tool_chain, "tool_chain", 1, seen, issues);
  checkChain(m, m.workpiece_chain, "workpiece_chain", 2, seen, issues);
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    if (seen[i] == 0) {
      issues.push_back({indexed("joints", i), "joint " + m.joints[i].name +
                                                  " is in neither tool_chain nor workpiece_chain"});
    }
  }
  const auto has = axisLetters(m);
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    const double h = m.home[static_cast<std::size_t>(a)];
    if (!std::isfinite(h)) {
      issues.push_back({std::string("home.") + gcode::kAxisLetters[a], "must be finite"});
    } else if (h != 0.0 && !has[static_cast<std::size_t>(a)]) {
      issues.push_back(
          {std::string("home.") + gcode::kAxisLetters[a], "the machine has no joint of that name"});
    }
  }
  if (unitDirection(m.spindle_axis) == glm::dvec3(0.0)) {
    issues.push_back({"spindle_axis", "must be a finite, non-zero direction"});
  }
  if (!(std::isfinite(m.rapid_feed) && m.rapid_feed > 0)) {
    issues.push_back({"rapid_feed", "must be a positive number (mm/min)"});
  }
  if (!(std::isfinite(m.max_feed) && m.max_feed > 0)) {
    issues.push_back({"max_feed", "must be a positive number (mm/min)"});
  }
  return issues;
}

}  // namespace mdhd::kin

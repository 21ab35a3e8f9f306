#include "sim/kinematics/kinematics.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace mdhd::kin {

void sinCosDegrees(double degrees, double& s, double& c) {
  // fmod is exact but costs; only reduce what is large enough to lose digits.
  double r = std::abs(degrees) > 360.0 ? std::fmod(degrees, 360.0) : degrees;  // (-360, 360)
  if (r > 180.0) r -= 360.0;
  if (r <= -180.0) r += 360.0;  // now (-180, 180], exact
  if (r == 0.0) {
    s = 0.0, c = 1.0;
  } else if (r == 90.0) {
    s = 1.0, c = 0.0;
  } else if (r == 180.0) {
    s = 0.0, c = -1.0;
  } else if (r == -90.0) {
    s = -1.0, c = 0.0;
  } else {
    const double rad = r * (std::numbers::pi / 180.0);
    s = std::sin(rad);
    c = std::cos(rad);
  }
}

Kinematics::Kinematics(Machine machine) : machine_(std::move(machine)) {
  const auto issues = validateMachine(machine_);
  if (!issues.empty()) {
    throw KinematicsError("machine." + issues.front().field + ": " + issues.front().message);
  }
  spindle_axis_ = unitDirection(machine_.spindle_axis);
  joint_of_axis_.fill(-1);
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    joint_of_axis_[a] = jointIndex(machine_, static_cast<gcode::Axis>(a));
    axes_[a] = joint_of_axis_[a] >= 0;
  }
  tool_count_ = fill(machine_, machine_.tool_chain, tool_);
  wp_count_ = fill(machine_, machine_.workpiece_chain, wp_);
}

Kinematics::ChainJoint Kinematics::compile(const Joint& joint) {
  ChainJoint c;
  c.axis = *axisOfName(joint.name);
  c.rotary = joint.type == JointType::kRotary;
  c.unit = unitDirection(joint.axis);
  c.origin = joint.origin;
  const glm::dvec3& u = c.unit;
  c.outer = glm::outerProduct(u, u);
  // glm is column-major: m[col][row].
  c.cross = glm::dmat3(0.0, u.z, -u.y,   // column 0
                       -u.z, 0.0, u.x,   // column 1
                       u.y, -u.x, 0.0);  // column 2
  return c;
}

int Kinematics::fill(const Machine& m, const std::vector<int>& indices, Chain& chain) {
  int n = 0;
  for (int j : indices) chain[static_cast<std::size_t>(n++)] = compile(m.joints[j]);
  return n;
}

Rigid Kinematics::compose(const Chain& chain, int count, const JointValues& q, glm::dmat3* xyz) {
  Rigid acc;
  bool turned = false;  // acc.rotation is still the identity: skip its products
  for (int i = 0; i < count; ++i) {
    const ChainJoint& j = chain[static_cast<std::size_t>(i)];
    const double v = q[static_cast<std::size_t>(j.axis)];
    if (!j.rotary) {
      const glm::dvec3 t = j.origin + v * j.unit;
      acc.translation += turned ? acc.rotation * t : t;
      if (xyz != nullptr && j.axis <= gcode::kZ) {
        (*xyz)[j.axis] = turned ? acc.rotation * j.unit : j.unit;
      }
      continue;
    }
    double s = 0.0;
    double c = 1.0;
    sinCosDegrees(v, s, c);
    // Rodrigues: R = c I + s [u]x + (1 - c) u u^T, about the line through origin.
    const glm::dmat3 r = c * glm::dmat3(1.0) + s * j.cross + (1.0 - c) * j.outer;
    const glm::dvec3 t = j.origin - r * j.origin;
    acc.translation += turned ? acc.rotation * t : t;
    acc.rotation = turned ? acc.rotation * r : r;
    turned = true;
  }
  return acc;
}

ToolPose Kinematics::toolPose(const JointValues& q, double length) const {
  const Rigid t = toolInWorkpiece(q);
  ToolPose p;
  p.axis = t.vector(spindle_axis_);
  p.tip = t.translation - length * p.axis;
  return p;
}

glm::dvec3 Kinematics::tipJacobian(const JointValues& q, double length, glm::dmat3& jac) const {
  glm::dmat3 toolDirs(0.0);
  glm::dmat3 wpDirs(0.0);
  const Rigid tool = compose(tool_, tool_count_, q, &toolDirs);
  const Rigid wp = compose(wp_, wp_count_, q, &wpDirs);
  // Tip in W = R_wp^T (tip in the machine - t_wp): a tool-chain joint moves the tip with
  // its direction, a workpiece-chain joint moves W, so the tip the opposite way.
  const glm::dmat3 rt = glm::transpose(wp.rotation);
  jac = rt * (toolDirs - wpDirs);
  return rt * (tool.point(-length * spindle_axis_) - wp.translation);
}

}  // namespace mdhd::kin

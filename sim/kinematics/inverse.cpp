#include "sim/kinematics/inverse.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace mdhd::kin {
namespace {

// Below this |det| of the unit-column Jacobian the linear joints are taken as
// dependent: the tip could only be reached with huge, meaningless joint moves.
constexpr double kSingularDet = 1e-9;

}  // namespace

bool solveTip(const Kinematics& kin, const glm::dvec3& tip, double length, JointValues& q) {
  if (!kin.hasXyz()) return false;
  glm::dmat3 jac;
  const glm::dvec3 now = kin.tipJacobian(q, length, jac);
  const double det = glm::determinant(jac);
  if (!(std::abs(det) > kSingularDet)) return false;
  const glm::dvec3 dx = glm::inverse(jac) * (tip - now);
  const glm::dvec3 x = glm::dvec3(q[gcode::kX], q[gcode::kY], q[gcode::kZ]) + dx;
  if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return false;
  q[gcode::kX] = x.x;
  q[gcode::kY] = x.y;
  q[gcode::kZ] = x.z;
  return true;
}

JointValues solveTipOrThrow(const Kinematics& kin, const glm::dvec3& tip, double length,
                            JointValues q) {
  if (!kin.hasXyz()) {
    throw KinematicsError("G43.4 needs linear joints X, Y and Z; the machine has " +
                          axisLetterString(kin.machine()));
  }
  if (!solveTip(kin, tip, length, q)) {
    std::string pose;
    for (int a = gcode::kA; a < gcode::kAxisCount; ++a) {
      if (a == gcode::kU) break;
      if (kin.hasAxis(static_cast<gcode::Axis>(a))) {
        pose += std::string(" ") + gcode::kAxisLetters[a] + std::to_string(q[a]);
      }
    }
    throw KinematicsError(
        "G43.4: the linear joints X, Y, Z cannot place the tool tip at this "
        "pose (singular):" +
        pose);
  }
  return q;
}

gcode::AxisValues switchTcp(const Kinematics& kin, const gcode::AxisValues& machine, double length,
                            bool to_tcp) {
  if (!to_tcp) return solveTipOrThrow(kin, {machine[0], machine[1], machine[2]}, length, machine);
  const glm::dvec3 tip = kin.toolPose(machine, length).tip;
  gcode::AxisValues out = machine;
  out[gcode::kX] = tip.x;
  out[gcode::kY] = tip.y;
  out[gcode::kZ] = tip.z;
  return out;
}

}  // namespace mdhd::kin

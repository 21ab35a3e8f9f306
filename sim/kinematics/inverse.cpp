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
  // Tip(x) = tip0 + J x exactly (affine), so the columns of J are differences of
  // tips at unit joint steps from x = 0.
  JointValues p = q;
  p[gcode::kX] = p[gcode::kY] = p[gcode::kZ] = 0.0;
  const glm::dvec3 tip0 = kin.toolPose(p, length).tip;
  glm::dmat3 jac;
  for (int i = 0; i < 3; ++i) {
    p[static_cast<std::size_t>(i)] = 1.0;
    jac[i] = kin.toolPose(p, length).tip - tip0;
    p[static_cast<std::size_t>(i)] = 0.0;
  }
  const double det = glm::determinant(jac);
  if (!(std::abs(det) > kSingularDet)) return false;
  const glm::dvec3 x = glm::inverse(jac) * (tip - tip0);
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

}  // namespace mdhd::kin

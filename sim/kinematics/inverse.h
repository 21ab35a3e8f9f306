#pragma once
// Tool centre point control (G43.4): with the rotary joints fixed the tip in W is
// an affine function of the linear joints X, Y, Z, so placing the tip is one 3x3
// linear solve.
#include "sim/kinematics/kinematics.h"

namespace mdhd::kin {

// Sets q's X, Y and Z so that a tool of `length` has its tip at `tip` (in W); every
// other joint keeps its value from q. Returns false, leaving q unchanged, when the
// machine lacks X, Y or Z or when they cannot move the tip in every direction at
// this pose (their directions in W are linearly dependent).
bool solveTip(const Kinematics& kin, const glm::dvec3& tip, double length, JointValues& q);

// The same, throwing KinematicsError with the reason instead of returning false.
JointValues solveTipOrThrow(const Kinematics& kin, const glm::dvec3& tip, double length,
                            JointValues q);

// G43.4 switched on or off with the machine at rest: its values re-expressed, to_tcp
// from joints to the tip in W of a tool of `length` (X Y Z), else back (solveTipOrThrow).
// What gcode::InterpreterConfig::tcp_switch asks of the machine.
gcode::AxisValues switchTcp(const Kinematics& kin, const gcode::AxisValues& machine, double length,
                            bool to_tcp);

}  // namespace mdhd::kin

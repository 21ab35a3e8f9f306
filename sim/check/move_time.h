#pragma once
// How long one motion takes at its programmed feed (or the machine's rapid rate),
// a first-order model without acceleration, as LinuxCNC plans a move's nominal
// time: the feed applies to the XYZ length, or to the rotary length (deg/min)
// when no linear axis moves. Stands in until kinematics' motion_time lands.
#include "sim/gcode/motion.h"
#include "sim/kinematics/joint_path.h"
#include "sim/kinematics/machine.h"

namespace mdhd::check {

struct MoveLength {
  double linear = 0.0;  // mm of X Y Z (U V W) as programmed (arcs along the arc)
  double rotary = 0.0;  // degrees of A B C
};

MoveLength moveLength(const gcode::Motion& m, const kin::JointPath& path);

// Seconds; 0 for a motion of no length. Feeds above the machine's max_feed are
// clamped to it (rapid_feed for G0).
double moveSeconds(const gcode::Motion& m, const MoveLength& length, const kin::Machine& machine);

}  // namespace mdhd::check

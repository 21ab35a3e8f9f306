#pragma once
// How long a machine takes for one interpreted motion, at the commanded feed,
// without acceleration (a lower bound of the real time, like LinuxCNC's
// estimate with infinite acceleration). Used by `mdhd check` (cycle time) and the
// simulated controller (`mdhd modbus-sim`), so both agree.
//
// Rules, in minutes:
// - G0: max over the joints of |travel| / rapid_feed (linear joints in mm, rotary in
//   degrees, each at rapid_feed): each joint at most at rapid speed, the slowest
//   decides, as LinuxCNC's rapid with one velocity for every axis. Under G43.4 a
//   linear joint's travel is the length of its solved path (sampled every degree of
//   rotary travel), not end - start.
// - G1/G2/G3 under G94: the programmed path length / min(F, max_feed). The length is
//   that of X Y Z (arcs: the helical length, radius averaged over the sweep); when X
//   Y Z do not move, that of U V W; when neither moves, the rotary travel
//   sqrt(dA^2 + dB^2 + dC^2) in degrees at F deg/min (capped at max_feed too).
//   Under G43.4 X Y Z are the tool tip, so the tip path sets the time.
// - G93: 1 / F (the motion's inverse_time), but no faster than max_feed allows.
// - G95: F mm/rev * spindle rpm as the feed, then as G94.
// - Dwell events: their seconds; other events take no time.
#include <stdexcept>

#include "sim/gcode/motion.h"
#include "sim/kinematics/kinematics.h"

namespace mdhd::kin {

class MotionTimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Seconds for the motion. `tool_length` is needed for G0 under G43.4, whose joint
// travel comes from solving the tip. Throws MotionTimeError for a feed motion that
// moves without a usable feed (F <= 0, G95 with the spindle stopped) or a machine
// without rapid_feed, and KinematicsError where JointPath does.
double motionSeconds(const gcode::Motion& motion, const Kinematics& kin, double tool_length);

// Seconds an event takes (dwell: its value; others 0).
double eventSeconds(const gcode::Event& event);

// The length in mm (or degrees for a pure rotary move) the feed applies to, as above.
double feedPathLength(const gcode::Motion& motion, const Kinematics& kin, double tool_length);

}  // namespace mdhd::kin

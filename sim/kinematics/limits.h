#pragma once
// Axis limits: of one joint vector, and of a whole JointPath, where arcs and tool
// centre point moves can leave a joint's range between their end points.
#include <optional>
#include <vector>

#include "sim/kinematics/joint_path.h"

namespace mdhd::kin {

// Values beyond a limit by no more than this (mm or degrees) are rounding, not travel.
inline constexpr double kLimitSlack = 1e-9;

struct LimitViolation {
  int joint = -1;  // index into machine.joints
  gcode::Axis axis = gcode::kX;
  double limit = 0.0;           // the bound that was crossed (min or max)
  double value = 0.0;           // the farthest value beyond it
  double excess = 0.0;          // |value - limit| > 0
  double first_s = 0.0;         // paths: where the joint first leaves its range
  double worst_s = 0.0;         // paths: where it reaches `value`
  bool outside_at_end = false;  // paths: the joint is still beyond this side at s = 1
  int side = 0;                 // +1: beyond max, -1: below min (the side of `limit`)
};

// The first joint (in machine order) outside its limits, if any.
std::optional<LimitViolation> checkLimits(const Kinematics& kin, const JointValues& q);

// The violation that starts earliest along the path (ties: machine order), if any.
// Joints linear in s are checked exactly; arc axes and joints solved under tcp by
// dense sampling (every 2 degrees of arc or rotary travel, at least 32 steps), with
// the arc's extreme angles added and every local extreme refined by golden section.
// Throws KinematicsError when a tcp path passes a singular pose.
std::optional<LimitViolation> checkLimits(const JointPath& path);

// Every joint that leaves its range along the path, one entry per joint and side (its
// first crossing of that side and its farthest value beyond it over the path), ordered
// by first_s (ties: machine order, then the side reached first). A move can take
// several joints beyond their limits; each is an overtravel. A joint that goes from
// below its min to beyond its max in one move (G0 X-60 then G0 X600 on X -50..550) has
// two entries: the min side (first_s 0, outside_at_end false: it left that side) and
// the max side (first_s where it crosses max, its own excess). Until session 23 that
// was one entry on the min side, and the max side's overtravel was never named.
std::vector<LimitViolation> checkLimitsAll(const JointPath& path);

}  // namespace mdhd::kin

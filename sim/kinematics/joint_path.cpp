#include "sim/kinematics/joint_path.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sim/kinematics/inverse.h"

namespace mdhd::kin {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::string where(const gcode::Motion& m) {
  return "line " + std::to_string(m.pos.line) + ": ";
}

// Non-finite values would pass every comparison of the limit checks unnoticed.
void checkFinite(const gcode::Motion& m, double length) {
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    if (!std::isfinite(m.start[a]) || !std::isfinite(m.end[a])) {
      throw KinematicsError(where(m) + "non-finite value of axis " + gcode::kAxisLetters[a]);
    }
  }
  if (m.type == gcode::MotionType::kArc &&
      (!std::isfinite(m.center[0]) || !std::isfinite(m.center[1]))) {
    throw KinematicsError(where(m) + "non-finite arc centre");
  }
  if (!std::isfinite(length)) throw KinematicsError(where(m) + "non-finite tool length");
}

}  // namespace

JointPath::JointPath(const Kinematics& kin, const gcode::Motion& motion, double tool_length)
    : kin_(&kin),
      start_(motion.start),
      end_(motion.end),
      length_(tool_length),
      tcp_(motion.tcp),
      arc_(motion.type == gcode::MotionType::kArc) {
  checkFinite(motion, tool_length);
  if (arc_) {
    switch (motion.plane) {
      case gcode::Plane::kXY:
        first_ = gcode::kX, second_ = gcode::kY;
        break;
      case gcode::Plane::kXZ:
        first_ = gcode::kZ, second_ = gcode::kX;
        break;
      case gcode::Plane::kYZ:
        first_ = gcode::kY, second_ = gcode::kZ;
        break;
    }
    if (motion.turn == 0) throw KinematicsError(where(motion) + "arc with turn 0");
    center_ = {motion.center[0], motion.center[1]};
    const double u0 = start_[first_] - center_.x;
    const double v0 = start_[second_] - center_.y;
    const double u1 = end_[first_] - center_.x;
    const double v1 = end_[second_] - center_.y;
    radius0_ = std::hypot(u0, v0);
    radius1_ = std::hypot(u1, v1);
    angle0_ = std::atan2(v0, u0);
    double sweep = std::atan2(v1, u1) - angle0_;
    if (motion.turn > 0) {
      if (sweep <= 0.0) sweep += kTwoPi;  // exact, as LinuxCNC's find_turn
      sweep += kTwoPi * (motion.turn - 1);
    } else {
      if (sweep >= 0.0) sweep -= kTwoPi;
      sweep += kTwoPi * (motion.turn + 1);
    }
    sweep_ = sweep;
  }
  start_joints_ = start_;
  end_joints_ = end_;
  if (tcp_) {
    try {
      start_joints_ = solveTipOrThrow(kin, {start_[0], start_[1], start_[2]}, length_, start_);
      end_joints_ = solveTipOrThrow(kin, {end_[0], end_[1], end_[2]}, length_, end_);
    } catch (const KinematicsError& e) {
      throw KinematicsError(where(motion) + e.what());
    }
  }
}

JointValues JointPath::programAt(double s) const {
  if (!(s > 0.0)) return start_;  // also NaN
  if (s >= 1.0) return end_;
  gcode::AxisValues v;
  for (std::size_t a = 0; a < v.size(); ++a) v[a] = start_[a] + (end_[a] - start_[a]) * s;
  if (arc_) {
    const double angle = angle0_ + sweep_ * s;
    const double r = radius0_ + (radius1_ - radius0_) * s;
    v[first_] = center_.x + r * std::cos(angle);
    v[second_] = center_.y + r * std::sin(angle);
  }
  return v;
}

JointValues JointPath::at(double s) const {
  if (!(s > 0.0)) return start_joints_;
  if (s >= 1.0) return end_joints_;
  const gcode::AxisValues v = programAt(s);
  if (!tcp_) return v;
  return solveTipOrThrow(*kin_, {v[0], v[1], v[2]}, length_, v);
}

}  // namespace mdhd::kin

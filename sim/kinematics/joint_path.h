#pragma once
// One interpreted motion as a path in joint space, s in [0, 1]:
// - G0/G1: every joint linear in s;
// - G2/G3: the two linear joints of the plane along the arc (radius blended from
//   start to end), the plane normal (helix) and every other joint linear in s;
// - G43.4 (motion.tcp): X Y Z of the motion are the tool tip in W; the tip moves on
//   the motion's line (or arc) in W, the rotary joints linearly in s, and X, Y, Z
//   are solved at each s.
#include "sim/gcode/motion.h"
#include "sim/kinematics/kinematics.h"

namespace mdhd::kin {

class JointPath {
 public:
  // `kin` must outlive the path. Throws KinematicsError for an arc with turn 0 or,
  // under tcp, when either end cannot be solved.
  JointPath(const Kinematics& kin, const gcode::Motion& motion, double tool_length);

  // The joint values at s (clamped to [0, 1]); at 0 and 1 the ends exactly.
  // Throws KinematicsError when a tcp path passes a singular pose.
  JointValues at(double s) const;

  // The motion's own axis values at s before any solving: joint values, or under
  // tcp with X Y Z the tool tip in W.
  JointValues programAt(double s) const;

  const JointValues& startJoints() const { return start_joints_; }
  const JointValues& endJoints() const { return end_joints_; }
  const Kinematics& kinematics() const { return *kin_; }
  double toolLength() const { return length_; }
  bool tcp() const { return tcp_; }
  bool isArc() const { return arc_; }
  // For arcs: the plane's two axes (first, second), the normal axis and the signed
  // sweep in radians (ccw about the normal positive).
  gcode::Axis arcFirst() const { return first_; }
  gcode::Axis arcSecond() const { return second_; }
  double arcSweep() const { return sweep_; }
  double arcStartAngle() const { return angle0_; }

 private:
  const Kinematics* kin_;
  gcode::AxisValues start_{};
  gcode::AxisValues end_{};
  JointValues start_joints_{};
  JointValues end_joints_{};
  double length_ = 0.0;
  bool tcp_ = false;
  bool arc_ = false;
  gcode::Axis first_ = gcode::kX;
  gcode::Axis second_ = gcode::kY;
  glm::dvec2 center_{0.0};
  double angle0_ = 0.0;
  double sweep_ = 0.0;
  double radius0_ = 0.0;
  double radius1_ = 0.0;
};

}  // namespace mdhd::kin

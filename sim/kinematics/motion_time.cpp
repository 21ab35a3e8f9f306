#include "sim/kinematics/motion_time.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "sim/kinematics/joint_path.h"

namespace mdhd::kin {
namespace {

using gcode::Axis;

double travel(const gcode::Motion& m, std::initializer_list<Axis> axes) {
  double sum = 0.0;
  for (Axis a : axes) {
    const double d = m.end[a] - m.start[a];
    sum += d * d;
  }
  return std::sqrt(sum);
}

// Helical length of an arc: the plane's two axes sweep around the centre (radius
// blended linearly from start to end), the third of X Y Z moves along the normal.
double arcLength(const gcode::Motion& m, const JointPath& path) {
  const Axis first = path.arcFirst();
  const Axis second = path.arcSecond();
  const Axis normal = static_cast<Axis>(3 - first - second);  // X+Y+Z indices sum to 3
  const double r0 = std::hypot(m.start[first] - m.center[0], m.start[second] - m.center[1]);
  const double r1 = std::hypot(m.end[first] - m.center[0], m.end[second] - m.center[1]);
  const double planar = 0.5 * (r0 + r1) * std::abs(path.arcSweep());
  const double along = m.end[normal] - m.start[normal];
  return std::hypot(planar, along);
}

std::string where(const gcode::Motion& m) {
  return "line " + std::to_string(m.pos.line) + ": ";
}

// Under G43.4 the linear joints follow the rotaries round: their travel is the length
// of their path, not end - start (a full table turn ends where it started, with X and
// Y having swung through 4 radii each). Sampled every degree of rotary travel.
double tcpJointTravel(const JointPath& path, Axis axis) {
  double degrees = 0.0;
  for (Axis r : {gcode::kA, gcode::kB, gcode::kC})
    degrees = std::max(degrees, std::abs(path.endJoints()[r] - path.startJoints()[r]));
  if (axis > gcode::kZ || degrees == 0.0) {
    // Rotaries (and U V W) move linearly; with the rotaries still so do X Y Z.
    return std::abs(path.endJoints()[axis] - path.startJoints()[axis]);
  }
  const int n = std::clamp(static_cast<int>(std::ceil(degrees)), 16, 400000);
  double sum = 0.0;
  double prev = path.startJoints()[axis];
  for (int i = 1; i <= n; ++i) {
    const double v = path.at(static_cast<double>(i) / n)[axis];
    sum += std::abs(v - prev);
    prev = v;
  }
  return sum;
}

double rapidMinutes(const gcode::Motion& m, const Kinematics& kin, double tool_length) {
  const double rapid = kin.machine().rapid_feed;
  if (!(rapid > 0.0)) throw MotionTimeError(where(m) + "the machine has no rapid_feed");
  // Under G43.4 the joints' travel differs from the motion's values: solve the path.
  const JointPath path(kin, m, tool_length);
  double longest = 0.0;
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    if (!kin.hasAxis(static_cast<Axis>(a))) continue;
    const double travel = path.tcp() ? tcpJointTravel(path, static_cast<Axis>(a))
                                     : std::abs(path.endJoints()[a] - path.startJoints()[a]);
    longest = std::max(longest, travel);
  }
  return longest / rapid;
}

}  // namespace

double feedPathLength(const gcode::Motion& m, const Kinematics& kin, double tool_length) {
  using gcode::kA, gcode::kB, gcode::kC, gcode::kU, gcode::kV, gcode::kW, gcode::kX, gcode::kY,
      gcode::kZ;
  double length = 0.0;
  if (m.type == gcode::MotionType::kArc) {
    length = arcLength(m, JointPath(kin, m, tool_length));
  } else {
    length = travel(m, {kX, kY, kZ});
  }
  if (length > 0.0) return length;
  length = travel(m, {kU, kV, kW});
  if (length > 0.0) return length;
  return travel(m, {kA, kB, kC});
}

double motionSeconds(const gcode::Motion& m, const Kinematics& kin, double tool_length) {
  if (m.type == gcode::MotionType::kRapid) return 60.0 * rapidMinutes(m, kin, tool_length);
  const double length = feedPathLength(m, kin, tool_length);
  if (length == 0.0) return 0.0;
  const double max_feed = kin.machine().max_feed;
  const double cap = max_feed > 0.0 ? max_feed : INFINITY;
  if (m.feed_mode == gcode::FeedMode::kInverseTime) {
    if (!(m.inverse_time > 0.0)) throw MotionTimeError(where(m) + "G93 move without an F word");
    return 60.0 * std::max(1.0 / m.inverse_time, length / cap);
  }
  double feed = m.feed;
  if (m.feed_mode == gcode::FeedMode::kUnitsPerRevolution) {
    if (m.spindle == gcode::SpindleState::kOff || !(m.spindle_rpm > 0.0)) {
      throw MotionTimeError(where(m) + "G95 feed per revolution with the spindle stopped");
    }
    feed = m.feed * m.spindle_rpm;
  }
  if (!(feed > 0.0)) throw MotionTimeError(where(m) + "feed move with F 0");
  return 60.0 * length / std::min(feed, cap);
}

double eventSeconds(const gcode::Event& e) {
  return e.type == gcode::EventType::kDwell ? std::max(0.0, e.value) : 0.0;
}

}  // namespace mdhd::kin

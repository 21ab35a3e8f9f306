#include "sim/check/move_time.h"

#include <algorithm>
#include <cmath>

namespace mdhd::check {
namespace {

constexpr gcode::Axis kLinearAxes[] = {gcode::kX, gcode::kY, gcode::kZ,
                                       gcode::kU, gcode::kV, gcode::kW};
constexpr gcode::Axis kRotaryAxes[] = {gcode::kA, gcode::kB, gcode::kC};

double normalAxisTravel(const gcode::Motion& m, const kin::JointPath& path) {
  double sum = 0.0;
  for (gcode::Axis a : kLinearAxes) {
    if (a == path.arcFirst() || a == path.arcSecond()) continue;
    const double d = m.end[a] - m.start[a];
    sum += d * d;
  }
  return sum;
}

}  // namespace

MoveLength moveLength(const gcode::Motion& m, const kin::JointPath& path) {
  MoveLength out;
  if (path.isArc()) {
    const int f = path.arcFirst(), s = path.arcSecond();
    const double r0 = std::hypot(m.start[f] - m.center[0], m.start[s] - m.center[1]);
    const double r1 = std::hypot(m.end[f] - m.center[0], m.end[s] - m.center[1]);
    const double inPlane = std::abs(path.arcSweep()) * 0.5 * (r0 + r1);
    out.linear = std::sqrt(inPlane * inPlane + normalAxisTravel(m, path));
  } else {
    double sum = 0.0;
    for (gcode::Axis a : kLinearAxes) {
      const double d = m.end[a] - m.start[a];
      sum += d * d;
    }
    out.linear = std::sqrt(sum);
  }
  double rot = 0.0;
  for (gcode::Axis a : kRotaryAxes) {
    const double d = m.end[a] - m.start[a];
    rot += d * d;
  }
  out.rotary = std::sqrt(rot);
  return out;
}

double moveSeconds(const gcode::Motion& m, const MoveLength& length, const kin::Machine& machine) {
  // Below a micron of linear travel the feed is taken as a rotary rate (LinuxCNC's rule).
  const double units = length.linear > 1e-6 ? length.linear : length.rotary;
  if (!(units > 0.0)) return 0.0;
  if (m.type == gcode::MotionType::kRapid) {
    return machine.rapid_feed > 0.0 ? units / machine.rapid_feed * 60.0 : 0.0;
  }
  double rate = m.feed;  // mm/min; G93 already converted by the interpreter
  if (m.feed_mode == gcode::FeedMode::kInverseTime && m.inverse_time > 0.0) {
    rate = units * m.inverse_time;
  } else if (m.feed_mode == gcode::FeedMode::kUnitsPerRevolution) {
    rate = m.feed * m.spindle_rpm;
  }
  if (machine.max_feed > 0.0 && (!(rate > 0.0) || rate > machine.max_feed)) rate = machine.max_feed;
  return rate > 0.0 ? units / rate * 60.0 : 0.0;
}

}  // namespace mdhd::check

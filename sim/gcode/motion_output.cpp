#include "sim/gcode/motion_output.h"

#include <cmath>
#include <numbers>

namespace mdhd::gcode {

PlaneAxes planeAxes(Plane p) {
  switch (p) {
    case Plane::kXZ:
      return {kZ, kX, kY};
    case Plane::kYZ:
      return {kY, kZ, kX};
    case Plane::kXY:
    default:
      return {kX, kY, kZ};
  }
}

AxisValues toMachine(const InterpState& s, const AxisValues& program) {
  AxisValues m;
  for (int i = 0; i < kAxisCount; ++i) m[i] = program[i] + s.g92[i];
  const double deg = s.rotation[s.coord_system];
  if (deg != 0.0) {
    const double t = deg * std::numbers::pi / 180.0;
    const double x = m[kX], y = m[kY];
    m[kX] = x * std::cos(t) - y * std::sin(t);
    m[kY] = x * std::sin(t) + y * std::cos(t);
  }
  const AxisValues& o = s.g5x[s.coord_system];
  for (int i = 0; i < kAxisCount; ++i) m[i] += o[i];
  if (s.tool_length_mode != 434) m[kZ] += s.tool_length;
  return m;
}

AxisValues toProgram(const InterpState& s, const AxisValues& machine) {
  AxisValues p = machine;
  if (s.tool_length_mode != 434) p[kZ] -= s.tool_length;
  const AxisValues& o = s.g5x[s.coord_system];
  for (int i = 0; i < kAxisCount; ++i) p[i] -= o[i];
  const double deg = s.rotation[s.coord_system];
  if (deg != 0.0) {
    const double t = -deg * std::numbers::pi / 180.0;
    const double x = p[kX], y = p[kY];
    p[kX] = x * std::cos(t) - y * std::sin(t);
    p[kY] = x * std::sin(t) + y * std::cos(t);
  }
  for (int i = 0; i < kAxisCount; ++i) p[i] -= s.g92[i];
  return p;
}

void MotionOutput::fill(MotionType type, const AxisValues& end, const InterpState& s,
                        const Block& block, const FeedInfo& feed, bool comp) {
  Motion& m = motion_;
  m.type = type;
  if (m.pos.file != block.pos.file) m.pos.file = block.pos.file;
  m.pos.line = block.pos.line;
  // An error of the motion (kinematics, simulation) points at its block's first word.
  m.pos.column = block.words.empty() ? 1 : block.words.front().column;
  m.block_text = &block.text;
  m.start = machine_;
  m.end = end;
  m.tcp = s.tool_length_mode == 434;
  m.plane = s.plane;
  m.turn = 0;
  m.center = {0.0, 0.0};
  m.feed_mode = feed.mode;
  m.inverse_time = feed.inverse_time;
  m.spindle_sync = feed.sync;
  m.feed = 0.0;
  if (type != MotionType::kRapid) {
    bool linear_moves = false, rotary_moves = false;
    for (int i = 0; i < kAxisCount; ++i) {
      const bool moved = std::fabs(end[i] - machine_[i]) > 1e-9;
      if (i == kA || i == kB || i == kC)
        rotary_moves |= moved;
      else
        linear_moves |= moved;
    }
    // Pure rotary moves: F is degrees per minute, never unit-converted.
    m.feed = (rotary_moves && !linear_moves && type != MotionType::kArc) ? feed.raw : feed.rate;
  }
  m.spindle_rpm = s.speed;
  m.spindle = s.spindle;
  m.tool = s.tool;
  m.comp = comp;
}

void MotionOutput::straight(MotionType type, const AxisValues& program_end, const InterpState& s,
                            const Block& block, const FeedInfo& feed, bool comp) {
  const AxisValues end = toMachine(s, program_end);
  fill(type, end, s, block, feed, comp);
  sink_.motion(motion_);
  machine_ = end;
}

void MotionOutput::arc(const AxisValues& program_end, double c1, double c2, int turn,
                       const InterpState& s, const Block& block, const FeedInfo& feed, bool comp) {
  const AxisValues end = toMachine(s, program_end);
  const PlaneAxes axes = planeAxes(s.plane);
  AxisValues centre = program_end;
  centre[axes.first] = c1;
  centre[axes.second] = c2;
  const AxisValues mc = toMachine(s, centre);
  fill(MotionType::kArc, end, s, block, feed, comp);
  motion_.center = {mc[axes.first], mc[axes.second]};
  motion_.turn = turn;
  sink_.motion(motion_);
  machine_ = end;
}

}  // namespace mdhd::gcode

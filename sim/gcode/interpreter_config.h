#pragma once
// How a machine and job set the interpreter up.
#include <array>
#include <functional>
#include <memory>
#include <string_view>

#include "sim/gcode/motion.h"
#include "sim/gcode/tool_table.h"

namespace mdhd::gcode {

class LineSource;

struct InterpreterConfig {
  // G54 .. G59.3: machine X Y Z at program zero (mm), the job's work_offsets.
  std::array<std::array<double, 3>, 9> work_offsets{};
  AxisValues home{};  // machine joint values when the program starts
  ToolTable tools;
  unsigned axis_mask = 0x3f;  // bit i: the machine has kAxisLetters[i] (default XYZABC)
  // Finds o<name> call files; empty or returning null: not found.
  std::function<std::unique_ptr<LineSource>(std::string_view name)> subroutine_loader;
  bool block_delete = false;
  // Where a G38.2..G38.5 move stops (machine values): given where it starts and
  // its target, returns true and sets `stop` when the probe trips (the machine
  // comes to rest at `stop`), false when it never trips. Unset: no probe model;
  // every probe move then runs to its target, the only thing a verifier can
  // assume without one (LinuxCNC itself re-reads the position after a probe).
  std::function<bool(const AxisValues& start, const AxisValues& target, AxisValues& stop)>
      probe_stop;
  // Splines (G5, G5.1, G5.2/G5.3) are handed on as feed moves along a polyline
  // that stays within this distance of the true curve (mm, > 0).
  double spline_tolerance = 0.001;
  // Called for every line read (a loop's and a subroutine's again): a caller's chance
  // to stop a run that makes no motion for a long time (an o-word loop of
  // assignments), by throwing. Unset: nothing.
  std::function<void()> each_line;
  // G43.4 switched on or off, or its tool changed: the machine does not move, but X Y Z
  // change meaning (under G43.4 the tip in W, else the linear joints). Returns `machine`
  // re-expressed: to_tcp, joints -> tip of a tool of `length`; else tip -> joints. May
  // throw std::exception (no joints place that tip): an error at the G43.4 / G49 word.
  // Unset: the values are kept as they are, which is right only where the tip in W is
  // the linear joints (no rotary joint turns the tool or the part).
  std::function<AxisValues(const AxisValues& machine, double length, bool to_tcp)> tcp_switch;
};

}  // namespace mdhd::gcode

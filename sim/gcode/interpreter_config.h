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
};

}  // namespace mdhd::gcode

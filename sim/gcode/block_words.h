#pragma once
// The words of one block sorted for execution: G and M codes by modal group,
// every other letter as a value with its column. Building it checks what can be
// checked without the machine state (unknown codes, two codes of one group,
// repeated letters, axis letters the machine lacks).
#include <array>
#include <cstdint>

#include "sim/gcode/block.h"
#include "sim/gcode/gcode_codes.h"

namespace mdhd::gcode {

struct BlockWords {
  std::array<int, kGGroupCount> g;         // code x10, -1: none
  std::array<int, kGGroupCount> g_column;  // column of that G word
  std::array<int, kMGroupCount> m;         // code x10, -1: none
  std::array<int, kMGroupCount> m_column;
  bool mist_and_flood = false;  // M7 and M8 on one line (the one allowed pair)
  std::uint32_t letters = 0;    // bit (c - 'A') for each letter other than G and M
  std::array<double, 26> value{};
  std::array<int, 26> column{};
  int axis_column = 0;  // column of the first axis word (X..W, @, ^), 0: none
  // Polar coordinates: @ radius, ^ angle (degrees). As rs274, a repeated one
  // is no error: the last one counts.
  bool has_radius = false, has_angle = false;
  double radius = 0.0, angle = 0.0;
  int polar_column = 0;    // column of the first @ or ^, 0: none
  int spindle_column = 0;  // column of the $ word (spindle select), 0: none
  bool hasPolar() const { return polar_column != 0; }

  bool has(char c) const { return (letters >> (c - 'A')) & 1u; }
  double get(char c) const { return value[c - 'A']; }
  int col(char c) const { return column[c - 'A']; }
  bool hasAxis() const { return axis_column != 0; }
};

// axis_mask: bit i set when the machine has axis kAxisLetters[i].
void readBlockWords(const Block& block, unsigned axis_mask, BlockWords& out);

// Error at a column of the block.
[[noreturn]] void failAt(const Block& block, int column, const std::string& message);

}  // namespace mdhd::gcode

#pragma once
// Tools the interpreter knows: number -> length (the Z offset G43 applies) and
// diameter (the D of G41/G42). Millimetres. LinuxCNC's .tbl text can be read
// into one (T<n> P<pocket> Z<len> D<dia>, ';' comments).
#include <string_view>
#include <vector>

namespace mdhd::gcode {

struct ToolEntry {
  int number = 0;
  double length = 0.0;    // mm
  double diameter = 0.0;  // mm
};

class ToolTable {
 public:
  void add(const ToolEntry& tool);  // replaces an entry with the same number
  const ToolEntry* find(int number) const;
  const std::vector<ToolEntry>& entries() const { return tools_; }

 private:
  std::vector<ToolEntry> tools_;
};

// Parses LinuxCNC tool table text; lengths are multiplied by mm_per_unit
// (25.4 for a table in inches). Throws GcodeError (line, column) on bad input.
ToolTable parseToolTable(std::string_view text, double mm_per_unit = 1.0);

}  // namespace mdhd::gcode

#include "sim/gcode/tool_table.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "sim/gcode/error.h"

namespace mdhd::gcode {

void ToolTable::add(const ToolEntry& tool) {
  for (ToolEntry& t : tools_) {
    if (t.number == tool.number) {
      t = tool;
      return;
    }
  }
  tools_.push_back(tool);
}

const ToolEntry* ToolTable::find(int number) const {
  for (const ToolEntry& t : tools_)
    if (t.number == number) return &t;
  return nullptr;
}

namespace {

[[noreturn]] void tableError(int line, int column, const std::string& what) {
  throw GcodeError(SourcePos{"tool table", line, column}, what);
}

// Parses one line (comment already cut off); returns false when it holds no tool.
bool parseToolLine(std::string_view code, int line, double scale, ToolEntry& tool) {
  bool has_t = false;
  std::size_t i = 0;
  while (i < code.size()) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(code[i])));
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    const int column = static_cast<int>(i) + 1;
    if (!std::isalpha(static_cast<unsigned char>(c)))
      tableError(line, column, "Bad tool table word");
    ++i;
    while (i < code.size() && code[i] == ' ') ++i;
    double value = 0.0;
    const char* first = code.data() + i;
    if (i < code.size() && code[i] == '+') ++first;
    auto [end, ec] = std::from_chars(first, code.data() + code.size(), value);
    if (ec != std::errc()) tableError(line, column, std::string("Bad number after '") + c + "'");
    i = static_cast<std::size_t>(end - code.data());
    if (c == 'T') {
      if (!(value >= 0 && value < 2147483648.0) || value != std::floor(value))
        tableError(line, column, "Bad tool number");
      tool.number = static_cast<int>(value);
      has_t = true;
    } else if (c == 'Z') {
      tool.length = value * scale;
    } else if (c == 'D') {
      tool.diameter = value * scale;
    }  // P (pocket), X Y A B C U V W I J Q: not used here
  }
  return has_t;
}

}  // namespace

ToolTable parseToolTable(std::string_view text, double mm_per_unit) {
  ToolTable table;
  int line = 0;
  while (!text.empty()) {
    ++line;
    const std::size_t nl = text.find('\n');
    std::string_view row = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    row = row.substr(0, row.find(';'));
    ToolEntry tool;
    if (parseToolLine(row, line, mm_per_unit, tool)) table.add(tool);
  }
  return table;
}

}  // namespace mdhd::gcode

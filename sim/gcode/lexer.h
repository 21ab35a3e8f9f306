#pragma once
// Lexing of one physical line, as LinuxCNC's "close and downcase": blanks
// outside comments vanish (so `G 0 X 1 . 5` reads as `g0x1.5`), letters are
// lower-cased, `( ... )` comments are kept verbatim, `;` ends the line. Each
// kept character remembers its column in the raw line, for error messages.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "sim/gcode/error.h"

namespace mdhd::gcode {

struct LineText {
  std::string code;          // normalized text
  std::vector<int> columns;  // 1-based raw column (in characters) of each code character
  int end_column = 1;        // column just after the last raw character (or at ';')
};

// Where errors of the current line are reported (no copies per line).
struct LineRef {
  const std::string* file = nullptr;
  int line = 0;
  SourcePos at(int column) const { return {file ? *file : std::string(), line, column}; }
};

// Fills `out` from `raw`; throws GcodeError for a nested or unclosed comment.
void normalizeLine(std::string_view raw, LineText& out, const LineRef& ref);

// Reading position in a normalized line.
class Cursor {
 public:
  Cursor(const LineText& text, const LineRef& ref) : text_(text), ref_(ref) {}

  bool atEnd() const { return index_ >= text_.code.size(); }
  char peek() const { return atEnd() ? '\0' : text_.code[index_]; }
  char peekAt(std::size_t ahead) const {
    const std::size_t i = index_ + ahead;
    return i < text_.code.size() ? text_.code[i] : '\0';
  }
  void advance(std::size_t n = 1) { index_ += n; }
  std::size_t index() const { return index_; }
  void setIndex(std::size_t index) { index_ = index; }
  std::string_view rest() const {
    return atEnd() ? std::string_view() : std::string_view(text_.code).substr(index_);
  }
  // Consumes `word` if the text continues with it.
  bool accept(std::string_view word);

  int columnAt(std::size_t index) const {
    return index < text_.columns.size() ? text_.columns[index] : text_.end_column;
  }
  int column() const { return columnAt(index_); }
  const LineRef& ref() const { return ref_; }

  [[noreturn]] void fail(const std::string& message) const { failAt(index_, message); }
  [[noreturn]] void failAt(std::size_t index, const std::string& message) const;

  // An unsigned decimal number: digits with an optional point (`1.`, `.5`,
  // `12.345`); the correctly rounded double. Errors worded as LinuxCNC's.
  double readUnsignedNumber();
  // The number of an N word: digits, optionally `.digits` (ignored by LinuxCNC).
  double readLineNumber();
  // A comment starting at '(' : returns its text without the parentheses.
  std::string_view readComment();

 private:
  const LineText& text_;
  const LineRef& ref_;
  std::size_t index_ = 0;
};

std::string badCharacterMessage(char c);

}  // namespace mdhd::gcode

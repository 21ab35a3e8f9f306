#pragma once
// Errors of the G-code layer. Every rejection names where (file, line, column)
// and what, in words a machinist understands.
#include <stdexcept>
#include <string>

namespace mdhd::gcode {

struct SourcePos {
  std::string file;  // empty: the main program; else an external subroutine file
  int line = 0;      // 1-based physical line
  int column = 0;    // 1-based column of the offending character or word
                     // in characters (UTF-8); 0 only outside a program (configuration)
};

class GcodeError : public std::runtime_error {
 public:
  GcodeError(SourcePos pos, const std::string& message)
      : std::runtime_error(message), pos_(std::move(pos)) {}
  const SourcePos& pos() const { return pos_; }
  int line() const { return pos_.line; }
  int column() const { return pos_.column; }

 private:
  SourcePos pos_;
};

}  // namespace mdhd::gcode

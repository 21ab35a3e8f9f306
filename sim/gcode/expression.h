#pragma once
// Values and `[ ]` expressions of RS274/NGC as LinuxCNC evaluates them:
// binary operators left to right by precedence (** > * / MOD > + - >
// comparisons > AND OR XOR), unary minus/plus binding to the value, functions
// in degrees, parameters read through the ParameterStore.
#include <string_view>

#include "sim/gcode/lexer.h"
#include "sim/gcode/parameters.h"

namespace mdhd::gcode {

// A reference to a parameter as written: `#12`, `##1`, `#[1+2]`, `#<name>`.
struct ParameterRef {
  bool named = false;
  int number = 0;
  std::string_view name;  // lower case, valid while the line is
  std::size_t index = 0;  // cursor index of the '#', for errors
};

class ExpressionReader {
 public:
  static constexpr int kMaxDepth = 64;  // brackets, functions, indirections, unary signs

  explicit ExpressionReader(const ParameterStore& params) : params_(params) {}

  // A real value after a word letter or '=': number, [expr], #param, function, -value.
  double readRealValue(Cursor& c);
  // A real value that must be an integer (parameter numbers).
  int readIntegerValue(Cursor& c);
  // `[ ... ]` at the cursor.
  double readExpression(Cursor& c);
  // `#...` at the cursor, without reading its value.
  ParameterRef readParameterRef(Cursor& c);
  double parameterValue(const ParameterRef& ref, const Cursor& c) const;

 private:
  double readBinary(Cursor& c, int min_precedence);
  double readFunction(Cursor& c);
  double readExists(Cursor& c);
  void enter(const Cursor& c);

  const ParameterStore& params_;
  int depth_ = 0;
};

}  // namespace mdhd::gcode

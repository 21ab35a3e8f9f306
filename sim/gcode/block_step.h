#pragma once
// Internal to BlockExecutor: the block being executed with its words and the
// working copy of the state that is committed when the block succeeds.
#include <string>

#include "sim/gcode/block_executor.h"

namespace mdhd::gcode {

struct BlockExecutor::Step {
  const Block& block;
  const BlockWords& w;
  InterpState& s;
  int motion = -1;  // motion code x10 to execute in this block, -1: none

  double unit() const { return s.inch ? kMmPerInch : 1.0; }
  // A length word in program units -> mm.
  double len(double v) const { return v * unit(); }
  double lenWord(char c) const { return w.get(c) * unit(); }
  [[noreturn]] void fail(const std::string& message, int column = 0) const {
    failAt(block, column, message);
  }
  [[noreturn]] void failWord(char c, const std::string& message) const {
    failAt(block, w.has(c) ? w.col(c) : 0, message);
  }
  // A word's value as an int (truncated); beyond an int's range, where a cast is
  // undefined, an error naming the word (the fuzzer's T5.5e11, H1.2e10).
  int intWord(char c) const {
    const double v = w.get(c);
    if (!(v > -2147483649.0 && v < 2147483648.0))
      failWord(c, std::string(1, c) + " word value out of range");
    return static_cast<int>(v);
  }
  int gColumn(int group) const { return w.g[group] >= 0 ? w.g_column[group] : 0; }
};

inline bool isCycle(int motion) {
  return motion == 730 || motion == 740 || (motion >= 810 && motion <= 890);
}

}  // namespace mdhd::gcode

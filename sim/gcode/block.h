#pragma once
// One block (line) of a program after reading: the words with their values
// already evaluated (expressions, parameters), comments and messages. This is
// the hand-over from the reader (text, parameters, O-word control flow) to the
// interpreter (modal state, motion).
#include <string>
#include <vector>

#include "sim/gcode/error.h"

namespace mdhd::gcode {

struct Word {
  char letter = 0;     // upper case: A..Z except N and O (those are consumed by the reader)
  double value = 0.0;  // evaluated value, in program units / degrees as written
  int column = 0;      // 1-based column where the word's letter stands
};

struct Block {
  SourcePos pos;                      // file and line; column 0
  std::string text;                   // the source line as written (for reports)
  std::vector<Word> words;            // in the order written
  std::vector<std::string> comments;  // "(...)" texts in order, without parentheses
  std::vector<std::string> messages;  // texts of (MSG,...) and (DEBUG,...) (evaluated)
  std::vector<std::string> prints;    // texts of (PRINT,...) (evaluated; LinuxCNC: to stderr)
  bool has_n = false;                 // an N word was present
  double n = 0.0;
};

}  // namespace mdhd::gcode

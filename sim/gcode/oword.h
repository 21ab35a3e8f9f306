#pragma once
// The head of an O-word line: `o100 while`, `o<name> call`, ... The reader
// uses it both to execute control flow and, cheaply, to skip lines while it
// looks for the matching `endif` / `endwhile` / `endsub`.
#include <cstddef>
#include <string>
#include <string_view>

#include "sim/gcode/expression.h"
#include "sim/gcode/lexer.h"

namespace mdhd::gcode {

enum class OKeyword {
  kSub,
  kEndSub,
  kCall,
  kReturn,
  kIf,
  kElseIf,
  kElse,
  kEndIf,
  kWhile,
  kEndWhile,
  kDo,
  kBreak,
  kContinue,
  kRepeat,
  kEndRepeat,
  kProgramNumber  // a bare `O1000` line: a Fanuc-style program number (LinuxCNC 2.9)
};

struct OWordHead {
  std::string label;  // "100" for o100 / o0100 / o[50*2], or the name of o<name>
  OKeyword keyword = OKeyword::kSub;
  std::size_t index = 0;  // cursor index of the 'o', for errors
};

std::string_view keywordName(OKeyword keyword);

// Moves the cursor past a block delete '/' (if any) and an N number; returns
// true if an O-word starts there. Does not throw.
bool startsWithOWord(Cursor& c);

// Reads `o<label><keyword>` at the cursor (which is at the 'o'); the cursor
// stops after the keyword. A numbered label may be any integer value, as in
// LinuxCNC (`o#1`, `o[10*2]`). Throws GcodeError for a bad label or keyword.
OWordHead readOWordHead(Cursor& c, ExpressionReader& expressions);

}  // namespace mdhd::gcode

#pragma once
// The G-code reader: program text -> evaluated blocks. It owns everything
// between the characters and the words: comments, parameters and their
// assignment, expressions, and O-word control flow (subroutines, if, loops),
// so the interpreter sees a flat sequence of blocks with plain numbers.
//
// Streaming: lines are read from a seekable LineSource; only byte offsets of
// loop starts and subroutine bodies are kept, so memory does not grow with
// the program's length.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "sim/gcode/block.h"
#include "sim/gcode/expression.h"
#include "sim/gcode/lexer.h"
#include "sim/gcode/oword.h"
#include "sim/gcode/parameters.h"
#include "sim/gcode/source.h"

namespace mdhd::gcode {

struct ReaderOptions {
  bool block_delete = false;              // true: lines starting with '/' are skipped (switch ON)
  std::uint64_t max_steps = 100'000'000;  // physical lines read in total (loops count again)
  int max_call_depth = 10;  // call levels incl. the program: 9 nested calls (LinuxCNC: 10)
  std::uint64_t max_loop_iterations = 10'000'000;  // per while / do / repeat loop
  std::function<void()> each_line;                 // called for every line read; may throw
};

// Returns the text of external subroutine `name` (o<name> call without a
// definition in the program), or null if there is none.
using SubroutineLoader = std::function<std::unique_ptr<LineSource>(std::string_view name)>;

// A loader that looks for <name>.ngc in each directory in turn.
SubroutineLoader makeDirectoryLoader(std::vector<std::string> directories);

class Reader {
 public:
  Reader(std::unique_ptr<LineSource> main, ParameterStore& params, SubroutineLoader loader = {},
         ReaderOptions options = {});
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  // The next block to execute; false at the end of the program (end of the
  // file or a closing '%'). Throws GcodeError for bad input. Every executed
  // line with a word, a comment or an N number is a block; blank lines,
  // O-word lines and lines that only set parameters are not (their settings
  // take effect before the next block is returned). Block::comments holds
  // every comment of the line (leading blanks dropped, as LinuxCNC); like
  // LinuxCNC only the last one can be a (MSG,) / (DEBUG,) / (PRINT,).
  // Reuses out's vectors and strings: pass the same Block every time.
  bool next(Block& out);

  std::uint64_t steps() const { return steps_; }
  // For #<_line> and #<_call_level>: the line being read (in its file) and the
  // subroutine call depth (0: the program).
  int currentLine() const { return ref_.line; }
  int callLevel() const { return static_cast<int>(frames_.size()) - 1; }
  // The program's first line was a '%' tape mark / a closing '%' line ended it.
  // LinuxCNC rejects a program that starts with '%' and reaches the end of
  // the file without the closing '%' or M2/M30 ("File ended with no percent
  // sign"); that check belongs to whoever knows about M2 (the interpreter).
  bool startedWithPercent() const { return percent_opened_; }
  bool endedAtPercent() const { return ended_ && ended_at_percent_; }

  static constexpr std::size_t kMaxOpenBlocks = 10'000;

 private:
  struct Source {
    std::unique_ptr<LineSource> lines;
    std::string file;  // "" for the main program
  };
  struct SubDef {
    int source = 0;
    std::uint64_t body = 0;  // offset of the line after `sub`
    int line = 0;            // line number of the `sub` line
  };
  enum class ControlKind { kIf, kWhile, kDo, kRepeat };
  struct Control {
    ControlKind kind = ControlKind::kIf;
    std::string label;
    std::uint64_t offset = 0;  // while: its own line; do/repeat: the line after
    int line = 0;              // line number of the while/do/repeat/if line
    int column = 1;            // column of its O-word, for errors
    std::uint64_t iterations = 0;
    std::uint64_t remaining = 0;  // repeat
    bool taken = false;           // if: a branch has run
  };
  struct Frame {
    int source = 0;
    std::string name;  // the subroutine; "" for the main program
    std::uint64_t return_offset = 0;
    int return_line = 0;
    std::vector<Control> controls;
  };
  struct Assignment {
    bool named = false;
    int number = 0;
    std::string name;
    double value = 0.0;
  };
  using NameHash = std::hash<std::string_view>;
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return NameHash{}(s); }
  };

  // reader.cpp: lines and blocks
  LineSource& source() { return *sources_[static_cast<std::size_t>(frames_.back().source)].lines; }
  bool readLine(int source_index);
  bool processLine(Block& out);
  bool isClosingPercent() const;
  void parseBlock(Cursor& c, Block& out);
  void readAssignment(Cursor& c);
  void applyAssignments();
  void handleComments(Block& out);
  std::string substituteParameters(std::string_view text, int column);
  std::vector<int> comment_columns_;

  // reader_oword.cpp: control flow
  void handleOWord(Cursor& c);
  void readTrailingComments(Cursor& c);
  double readCondition(Cursor& c, const OWordHead& head);
  void defineSub(const OWordHead& head);
  void callSub(Cursor& c, const OWordHead& head);
  void returnFromSub(Cursor& c, const OWordHead& head);
  const SubDef& findSub(const std::string& label, const Cursor& c);
  bool scanForSub(int source_index, const std::string& label);
  std::string fileName(int source_index) const;
  void handleIf(Cursor& c, const OWordHead& head);
  void handleWhile(Cursor& c, const OWordHead& head);
  void handleLoopEnd(Cursor& c, const OWordHead& head);
  void handleBreakOrContinue(const OWordHead& head);
  // Where an O-word block opened: its line and the column of its O-word.
  struct Opened {
    int line = 0;
    int column = 1;
  };
  Opened openedHere(const OWordHead& head) const;
  void skipIfBranches(const std::string& label, Opened from);
  OKeyword skipTo(const std::string& label, std::initializer_list<OKeyword> stops, Opened from,
                  std::string_view what, bool in_definition = false);
  Control& pushControl(std::vector<Control>& controls);
  Control& topControl(ControlKind kind, const OWordHead& head, const Cursor& c);
  void countIteration(Control& control);
  // LinuxCNC keeps one if / while / do / repeat line per label in the program and in
  // each subroutine (subroutine names are apart): the first such line met claims the
  // label; another line with it is an error, except a while that closes a do and a
  // second do, which loops back to the first. claimLabel records or checks and returns
  // the claim; checkLabel only checks (blocks of the label met while skipping).
  struct LabelClaim {
    ControlKind kind = ControlKind::kIf;
    int source = 0;
    int line = 0;
    int column = 1;
    std::uint64_t offset = 0;  // do: the line after it
  };
  const LabelClaim& claimLabel(const OWordHead& head, ControlKind kind);
  void checkLabel(const OWordHead& head, ControlKind kind, const LabelClaim& claim) const;
  std::string labelKey(const std::string& label) const;
  // An error of a whole line or block: `column` is where its first word (or O-word) stands.
  [[noreturn]] void failLine(int line, int column, const std::string& message) const;
  int firstColumn() const { return text_.columns.empty() ? 1 : text_.columns.front(); }

  std::deque<Source> sources_;  // deque: a Source never moves (LineRef points at its name)
  ParameterStore& params_;
  SubroutineLoader loader_;
  ReaderOptions options_;
  ExpressionReader expressions_;
  std::unordered_map<std::string, SubDef, Hash, std::equal_to<>> subs_;
  std::unordered_map<std::string, LabelClaim, Hash, std::equal_to<>> label_claims_;
  std::vector<Frame> frames_;
  std::vector<Assignment> assignments_;  // reused: no allocation per line
  std::size_t assignment_count_ = 0;
  std::string raw_;
  LineText text_;
  LineRef ref_;
  std::uint64_t line_start_ = 0;
  std::uint64_t steps_ = 0;
  bool percent_opened_ = false;
  bool ended_at_percent_ = false;
  bool ended_ = false;
};

}  // namespace mdhd::gcode

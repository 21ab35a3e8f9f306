// O-word control flow of the Reader: subroutines, if/elseif/else, while,
// do-while, repeat, break and continue, with LinuxCNC's rules. Jumps are
// seeks to remembered byte offsets; skipping reads forward to the matching
// O-word of the same label.
#include <cmath>

#include "sim/gcode/reader.h"

namespace mdhd::gcode {
namespace {

std::string labelText(std::string_view label) {
  return "o<" + std::string(label) + ">";
}

std::string_view kindName(int kind) {
  static constexpr std::string_view kNames[] = {"if", "while", "do", "repeat"};
  return kNames[kind];
}

}  // namespace

void Reader::handleOWord(Cursor& c) {
  const OWordHead head = readOWordHead(c, expressions_);
  switch (head.keyword) {
    case OKeyword::kSub:
      readTrailingComments(c);
      defineSub(head);
      return;
    case OKeyword::kEndSub:
    case OKeyword::kReturn:
      returnFromSub(c, head);
      return;
    case OKeyword::kCall:
      callSub(c, head);
      return;
    case OKeyword::kIf:
    case OKeyword::kElseIf:
    case OKeyword::kElse:
    case OKeyword::kEndIf:
      handleIf(c, head);
      return;
    case OKeyword::kWhile:
    case OKeyword::kDo:
    case OKeyword::kRepeat:
      handleWhile(c, head);
      return;
    case OKeyword::kEndWhile:
    case OKeyword::kEndRepeat:
      handleLoopEnd(c, head);
      return;
    case OKeyword::kBreak:
    case OKeyword::kContinue:
      readTrailingComments(c);
      handleBreakOrContinue(head);
      return;
    case OKeyword::kProgramNumber:
      // `O1000` alone: LinuxCNC 2.9 runs on into it as a Fanuc-style program; inside
      // an O-word subroutine it is an error (such programs are only for M98).
      readTrailingComments(c);
      if (frames_.size() > 1) {
        c.failAt(head.index, "Fanuc-style program number " + labelText(head.label) +
                                 " inside subroutine " + labelText(frames_.back().name) +
                                 " (LinuxCNC runs 'O....' subprograms only by M98, which mdhd "
                                 "does not support)");
      }
      return;
  }
}

// After an O-word command only comments may follow (LinuxCNC).
void Reader::readTrailingComments(Cursor& c) {
  while (!c.atEnd()) {
    if (c.peek() != '(') c.fail("Unexpected character after O-word");
    c.readComment();
  }
}

double Reader::readCondition(Cursor& c, const OWordHead& head) {
  if (c.peek() != '[') {
    c.fail("Left bracket missing after '" + std::string(keywordName(head.keyword)) + "'");
  }
  const double value = expressions_.readExpression(c);
  readTrailingComments(c);
  return value;
}

// A definition is skipped, not run: remember where the body starts.
void Reader::defineSub(const OWordHead& head) {
  const int line = ref_.line;
  const SubDef def{frames_.back().source, source().tell(), line};
  if (const auto it = subs_.find(head.label); it != subs_.end()) {
    const SubDef& old = it->second;
    // Found before by looking ahead for a call: then it is this same definition.
    if (old.source != def.source || old.body != def.body) {
      failLine(line, openedHere(head).column,
               "Redefining subroutine " + labelText(head.label) + ", already defined in " +
                   fileName(old.source) + " line " + std::to_string(old.line));
    }
  }
  subs_[head.label] = def;
  skipTo(head.label, {OKeyword::kEndSub}, openedHere(head), "sub", true);
}

std::string Reader::fileName(int source_index) const {
  const std::string& file = sources_[static_cast<std::size_t>(source_index)].file;
  return file.empty() ? std::string("the program") : file;
}

// As LinuxCNC: a sub not yet defined is looked for in <name>.ngc first, then
// further on in the current file.
const Reader::SubDef& Reader::findSub(const std::string& label, const Cursor& c) {
  if (const auto it = subs_.find(label); it != subs_.end()) return it->second;
  const int here = frames_.back().source;
  const int line = ref_.line;
  const auto restorePosition = [&] {
    ref_.file = &sources_[static_cast<std::size_t>(here)].file;
    ref_.line = line;
  };
  if (loader_) {
    if (std::unique_ptr<LineSource> lines = loader_(label)) {
      sources_.push_back(Source{std::move(lines), label + ".ngc"});
      const int index = static_cast<int>(sources_.size()) - 1;
      if (scanForSub(index, label)) return subs_.find(label)->second;
      restorePosition();
      c.failAt(0, "File " + label + ".ngc does not define " + labelText(label) + " sub");
    }
  }
  if (scanForSub(here, label)) return subs_.find(label)->second;
  restorePosition();
  c.failAt(0, "Unknown subroutine " + labelText(label) + ": not defined in the program and no " +
                  label + ".ngc found");
}

// Looks ahead in a source for `o<label> sub` and records it; the source's
// position is restored.
bool Reader::scanForSub(int source_index, const std::string& label) {
  LineSource& lines = *sources_[static_cast<std::size_t>(source_index)].lines;
  const std::uint64_t back = lines.tell();
  const int back_line = lines.lineNumber();
  const std::uint64_t saved_start = line_start_;
  bool found = false;
  while (readLine(source_index)) {
    if (source_index == 0 && isClosingPercent()) break;
    Cursor c(text_, ref_);
    if (!startsWithOWord(c)) continue;
    const OWordHead head = readOWordHead(c, expressions_);
    if (head.keyword == OKeyword::kSub && head.label == label) {
      subs_[head.label] = SubDef{source_index, lines.tell(), lines.lineNumber()};
      found = true;
      break;
    }
  }
  lines.seek(back);
  lines.setLineNumber(back_line);
  line_start_ = saved_start;
  return found;
}

void Reader::callSub(Cursor& c, const OWordHead& head) {
  std::array<double, ParameterStore::kLocalCount> args{};
  int count = 0;
  while (c.peek() == '[' || c.peek() == '(') {  // comments may stand between arguments
    if (c.peek() == '(') {
      c.readComment();
      continue;
    }
    if (count == ParameterStore::kLocalCount)
      c.fail("Too many subroutine arguments (more than 30)");
    args[static_cast<std::size_t>(count++)] = expressions_.readExpression(c);
  }
  readTrailingComments(c);
  // LinuxCNC: call levels 0 (the program) to max_call_depth - 1.
  const int level = static_cast<int>(frames_.size());
  if (level >= options_.max_call_depth) {
    c.failAt(head.index, "Too many nested subroutine calls (limit " +
                             std::to_string(options_.max_call_depth) + " levels)");
  }
  LineSource& caller = source();
  const std::uint64_t return_offset = caller.tell();
  const int return_line = caller.lineNumber();
  const SubDef def = findSub(head.label, c);
  Frame& frame = frames_.emplace_back();
  frame.source = def.source;
  frame.name = head.label;
  frame.return_offset = return_offset;
  frame.return_line = return_line;
  params_.enterCall(args.data(), count);
  LineSource& callee = source();
  callee.seek(def.body);
  callee.setLineNumber(def.line);
}

void Reader::returnFromSub(Cursor& c, const OWordHead& head) {
  std::optional<double> value;
  if (c.peek() == '[') value = expressions_.readExpression(c);
  readTrailingComments(c);
  const std::string what(keywordName(head.keyword));
  if (frames_.size() <= 1) {
    c.failAt(head.index, labelText(head.label) + " " + what + " outside a subroutine");
  }
  if (frames_.back().name != head.label) {
    c.failAt(head.index, labelText(head.label) + " " + what + " inside subroutine " +
                             labelText(frames_.back().name));
  }
  params_.setReturnValue(value);
  params_.leaveCall();
  const Frame frame = std::move(frames_.back());
  frames_.pop_back();
  LineSource& caller = source();
  caller.seek(frame.return_offset);
  caller.setLineNumber(frame.return_line);
}

// Open if / loop blocks of one call level. Their number is capped so that a
// program opening blocks it never closes cannot grow memory without bound.
Reader::Control& Reader::pushControl(std::vector<Control>& controls) {
  if (controls.size() >= kMaxOpenBlocks) {
    failLine(ref_.line, firstColumn(),
             "Too many nested O-word blocks (more than " + std::to_string(kMaxOpenBlocks) +
                 " open if / while / do / repeat)");
  }
  return controls.emplace_back();
}

Reader::Control& Reader::topControl(ControlKind kind, const OWordHead& head, const Cursor& c) {
  std::vector<Control>& controls = frames_.back().controls;
  if (controls.empty() || controls.back().kind != kind || controls.back().label != head.label) {
    static constexpr std::string_view kOpeners[] = {"if", "while", "do", "repeat"};
    c.failAt(head.index, labelText(head.label) + " " + std::string(keywordName(head.keyword)) +
                             " without matching " + std::string(kOpeners[static_cast<int>(kind)]));
  }
  return controls.back();
}

void Reader::handleIf(Cursor& c, const OWordHead& head) {
  std::vector<Control>& controls = frames_.back().controls;
  switch (head.keyword) {
    case OKeyword::kIf: {
      const bool condition = readCondition(c, head) != 0.0;
      claimLabel(head, ControlKind::kIf);
      Control& control = pushControl(controls);
      control.kind = ControlKind::kIf;
      control.label = head.label;
      control.line = ref_.line;
      control.column = openedHere(head).column;
      if (condition) {
        control.taken = true;
      } else {
        skipIfBranches(head.label, {control.line, control.column});
      }
      return;
    }
    case OKeyword::kElseIf:
    case OKeyword::kElse: {
      // Reached while running a branch: the if is done.
      if (head.keyword == OKeyword::kElse) readTrailingComments(c);
      const Control open = topControl(ControlKind::kIf, head, c);  // a copy: skipTo reads on
      skipTo(head.label, {OKeyword::kEndIf}, {open.line, open.column}, "if");
      frames_.back().controls.pop_back();
      return;
    }
    default:  // endif
      readTrailingComments(c);
      topControl(ControlKind::kIf, head, c);
      controls.pop_back();
      return;
  }
}

// Skips branches not taken until an elseif whose condition holds, an else,
// or the endif (which closes the if). A loop, not recursion: a chain of
// elseif lines can be long.
void Reader::skipIfBranches(const std::string& label, Opened from) {
  for (;;) {
    const OKeyword stop =
        skipTo(label, {OKeyword::kElseIf, OKeyword::kElse, OKeyword::kEndIf}, from, "if");
    Cursor c(text_, ref_);
    startsWithOWord(c);
    const OWordHead head = readOWordHead(c, expressions_);
    if (stop == OKeyword::kEndIf) {
      readTrailingComments(c);
      frames_.back().controls.pop_back();
      return;
    }
    if (stop == OKeyword::kElse) {
      readTrailingComments(c);
      frames_.back().controls.back().taken = true;
      return;
    }
    if (readCondition(c, head) != 0.0) {
      frames_.back().controls.back().taken = true;
      return;
    }
  }
}

void Reader::handleWhile(Cursor& c, const OWordHead& head) {
  std::vector<Control>& controls = frames_.back().controls;
  const bool top_matches = !controls.empty() && controls.back().label == head.label;
  if (head.keyword == OKeyword::kDo) {
    readTrailingComments(c);
    // A do whose label an earlier do claimed loops back to that one (LinuxCNC).
    const LabelClaim claim = claimLabel(head, ControlKind::kDo);
    const bool earlier_do = claim.kind == ControlKind::kDo;
    Control& control = pushControl(controls);
    control.kind = ControlKind::kDo;
    control.label = head.label;
    control.offset = earlier_do ? claim.offset : source().tell();
    control.line = earlier_do ? claim.line : ref_.line;
    control.column = earlier_do ? claim.column : openedHere(head).column;
    return;
  }
  if (head.keyword == OKeyword::kRepeat) {
    const double count = std::nearbyint(readCondition(c, head));  // LinuxCNC rounds the count
    claimLabel(head, ControlKind::kRepeat);
    const Opened here = openedHere(head);
    if (!(count >= 1.0)) {
      skipTo(head.label, {OKeyword::kEndRepeat}, here, "repeat");
      return;
    }
    Control& control = pushControl(controls);
    control.kind = ControlKind::kRepeat;
    control.label = head.label;
    control.offset = source().tell();
    control.line = here.line;
    control.column = here.column;
    control.remaining = count >= 1e18 ? ~std::uint64_t{0} : static_cast<std::uint64_t>(count);
    return;
  }
  // while: the end of a do-while, a loop coming round again, or a new loop.
  const bool condition = readCondition(c, head) != 0.0;
  claimLabel(head, ControlKind::kWhile);
  if (top_matches && controls.back().kind == ControlKind::kDo) {
    Control& control = controls.back();
    if (condition) {
      countIteration(control);
      source().seek(control.offset);
      source().setLineNumber(control.line);
    } else {
      controls.pop_back();
    }
    return;
  }
  const bool again = top_matches && controls.back().kind == ControlKind::kWhile &&
                     controls.back().offset == line_start_;
  if (condition) {
    if (!again) {
      Control& control = pushControl(controls);
      control.kind = ControlKind::kWhile;
      control.label = head.label;
      control.offset = line_start_;
      control.line = ref_.line;
      control.column = openedHere(head).column;
    }
    return;
  }
  const Opened here = openedHere(head);
  if (again) controls.pop_back();
  skipTo(head.label, {OKeyword::kEndWhile}, here, "while");
}

void Reader::handleLoopEnd(Cursor& c, const OWordHead& head) {
  readTrailingComments(c);
  if (head.keyword == OKeyword::kEndWhile) {
    Control& control = topControl(ControlKind::kWhile, head, c);
    countIteration(control);
    source().seek(control.offset);
    source().setLineNumber(control.line - 1);  // the while line is read again
    return;
  }
  Control& control = topControl(ControlKind::kRepeat, head, c);
  if (--control.remaining == 0) {
    frames_.back().controls.pop_back();
    return;
  }
  countIteration(control);
  source().seek(control.offset);
  source().setLineNumber(control.line);
}

std::string Reader::labelKey(const std::string& label) const {
  std::string key = frames_.back().name;  // "" in the program; sub names are non-empty
  key += '\n';
  key += label;
  return key;
}

const Reader::LabelClaim& Reader::claimLabel(const OWordHead& head, ControlKind kind) {
  const auto [it, inserted] = label_claims_.try_emplace(labelKey(head.label));
  if (inserted) {
    LabelClaim& claim = it->second;
    claim.kind = kind;
    claim.source = frames_.back().source;
    claim.line = ref_.line;
    claim.column = openedHere(head).column;
    claim.offset = kind == ControlKind::kDo ? source().tell() : 0;
  } else {
    checkLabel(head, kind, it->second);
  }
  return it->second;
}

void Reader::checkLabel(const OWordHead& head, ControlKind kind, const LabelClaim& claim) const {
  if (kind == ControlKind::kDo) return;
  if (kind == ControlKind::kWhile && claim.kind == ControlKind::kDo) return;  // closes the do
  if (claim.source == frames_.back().source && claim.line == ref_.line) return;
  failLine(ref_.line, openedHere(head).column,
           "Duplicate O-word label " + labelText(head.label) + ": " +
               std::string(kindName(static_cast<int>(kind))) + " here, but line " +
               std::to_string(claim.line) + " already opens " + labelText(head.label) + " " +
               std::string(kindName(static_cast<int>(claim.kind))) +
               " (LinuxCNC: one if / while / do / repeat line per label in the program and in "
               "each subroutine)");
}

Reader::Opened Reader::openedHere(const OWordHead& head) const {
  return {ref_.line, head.index < text_.columns.size() ? text_.columns[head.index] : 1};
}

void Reader::countIteration(Control& control) {
  if (++control.iterations >= options_.max_loop_iterations) {
    failLine(control.line, control.column,
             "Loop " + labelText(control.label) + " ran more than " +
                 std::to_string(options_.max_loop_iterations) + " times (endless loop?)");
  }
}

// LinuxCNC allows break and continue for while and do loops only.
void Reader::handleBreakOrContinue(const OWordHead& head) {
  std::vector<Control>& controls = frames_.back().controls;
  const auto isLoop = [&](const Control& control) {
    return control.label == head.label &&
           (control.kind == ControlKind::kWhile || control.kind == ControlKind::kDo);
  };
  std::size_t i = controls.size();
  while (i > 0 && !isLoop(controls[i - 1])) --i;
  if (i == 0) {
    failLine(ref_.line, openedHere(head).column,
             labelText(head.label) + " " + std::string(keywordName(head.keyword)) +
                 ": no matching while/do label");
  }
  controls.resize(i);  // leave any if inside the loop
  const Control loop = controls.back();
  const bool is_while = loop.kind == ControlKind::kWhile;
  const OKeyword end = is_while ? OKeyword::kEndWhile : OKeyword::kWhile;
  const std::string_view what = is_while ? "while" : "do";
  if (head.keyword == OKeyword::kBreak) {
    controls.pop_back();
    skipTo(head.label, {end}, {loop.line, loop.column}, what);
    return;
  }
  if (is_while) {  // continue: test the condition again
    countIteration(controls.back());
    source().seek(loop.offset);
    source().setLineNumber(loop.line - 1);
    return;
  }
  // continue in a do loop: go to its closing while and let the condition decide.
  skipTo(head.label, {end}, {loop.line, loop.column}, what);
  Cursor c(text_, ref_);
  startsWithOWord(c);
  handleOWord(c);
}

OKeyword Reader::skipTo(const std::string& label, std::initializer_list<OKeyword> stops,
                        Opened from, std::string_view what, bool in_definition) {
  const int source_index = frames_.back().source;
  while (readLine(source_index)) {
    if (isClosingPercent()) break;
    Cursor c(text_, ref_);
    if (!startsWithOWord(c)) continue;
    const std::size_t at = c.index();
    const OWordHead head = readOWordHead(c, expressions_);
    if (in_definition && head.keyword == OKeyword::kSub) {
      c.failAt(at, "Nested subroutine definition: " + labelText(head.label) + " sub inside " +
                       labelText(label) + " sub");
    }
    if (in_definition && head.keyword == OKeyword::kProgramNumber) {
      c.failAt(at, "Nested subroutine definition: Fanuc-style program number " +
                       labelText(head.label) + " inside " + labelText(label) + " sub");
    }
    if (head.label != label) continue;
    for (OKeyword stop : stops) {
      if (head.keyword == stop) return stop;
    }
    // LinuxCNC reads the blocks of the label it skips to: another if / while / repeat
    // line of that label is a duplicate.
    if (in_definition) continue;
    const auto claimed = label_claims_.find(labelKey(label));
    if (claimed == label_claims_.end()) continue;
    if (head.keyword == OKeyword::kIf) checkLabel(head, ControlKind::kIf, claimed->second);
    if (head.keyword == OKeyword::kWhile) checkLabel(head, ControlKind::kWhile, claimed->second);
    if (head.keyword == OKeyword::kRepeat) checkLabel(head, ControlKind::kRepeat, claimed->second);
  }
  std::string wanted;
  for (OKeyword stop : stops) {
    if (!wanted.empty()) wanted += " / ";
    wanted += std::string(keywordName(stop));
  }
  failLine(from.line, from.column,
           labelText(label) + " " + std::string(what) + " has no matching " + wanted);
}

}  // namespace mdhd::gcode

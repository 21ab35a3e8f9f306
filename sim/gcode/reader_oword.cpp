// O-word control flow of the Reader: subroutines, if/elseif/else, while,
// do-while, repeat, break and continue. Jumps are seeks to remembered byte
// offsets; skipping reads forward to the matching O-word of the same label.
#include <cmath>

#include "sim/gcode/reader.h"

namespace mdhd::gcode {
namespace {

std::string labelText(std::string_view label) {
  return "o<" + std::string(label) + ">";
}

}  // namespace

void Reader::handleOWord(Cursor& c) {
  const OWordHead head = readOWordHead(c);
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
  }
}

void Reader::readTrailingComments(Cursor& c) {
  while (!c.atEnd()) {
    if (c.peek() != '(') c.fail("Unexpected text after O-word command");
    c.readComment();
  }
}

double Reader::readCondition(Cursor& c, const OWordHead& head) {
  if (c.peek() != '[') {
    c.fail("Expression in [ ] expected after " + labelText(head.label) + " " +
           std::string(keywordName(head.keyword)));
  }
  const double value = expressions_.readExpression(c);
  readTrailingComments(c);
  return value;
}

// A definition is skipped, not run: remember where the body starts.
void Reader::defineSub(const OWordHead& head) {
  const int line = ref_.line;
  const std::string label(head.label);
  subs_[label] = SubDef{frames_.back().source, source().tell(), line};
  skipTo(label, {OKeyword::kEndSub}, line, "sub");
}

const Reader::SubDef& Reader::findSub(std::string_view label, const Cursor& c) {
  if (const auto it = subs_.find(label); it != subs_.end()) return it->second;
  // Defined later in this file? Look ahead, then come back.
  const int here = frames_.back().source;
  const std::string name(label);
  const int line = ref_.line;
  if (scanForSub(here, name)) return subs_.find(name)->second;
  if (loader_) {
    if (std::unique_ptr<LineSource> lines = loader_(name)) {
      sources_.push_back(Source{std::move(lines), name + ".ngc"});
      const int index = static_cast<int>(sources_.size()) - 1;
      if (scanForSub(index, name)) return subs_.find(name)->second;
      ref_.file = &sources_[static_cast<std::size_t>(here)].file;
      ref_.line = line;
      c.failAt(0, "File " + name + ".ngc does not define o<" + name + "> sub");
    }
  }
  ref_.file = &sources_[static_cast<std::size_t>(here)].file;
  ref_.line = line;
  c.failAt(0, "Unknown subroutine o<" + name + ">: not defined in the program and no " + name +
                  ".ngc found");
}

bool Reader::scanForSub(int source_index, std::string_view label) {
  LineSource& lines = *sources_[static_cast<std::size_t>(source_index)].lines;
  const std::uint64_t back = lines.tell();
  const int back_line = lines.lineNumber();
  const std::uint64_t saved_start = line_start_;
  bool found = false;
  while (readLine(source_index)) {
    if (source_index == 0 && isClosingPercent()) break;
    Cursor c(text_, ref_);
    if (!startsWithOWord(c)) continue;
    const OWordHead head = readOWordHead(c);
    if (head.keyword == OKeyword::kSub && head.label == label) {
      subs_[std::string(label)] = SubDef{source_index, lines.tell(), lines.lineNumber()};
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
  while (c.peek() == '[') {
    if (count == ParameterStore::kLocalCount)
      c.fail("Too many subroutine arguments (more than 30)");
    args[static_cast<std::size_t>(count++)] = expressions_.readExpression(c);
  }
  readTrailingComments(c);
  const int depth = static_cast<int>(frames_.size());  // the new call's level
  if (depth > options_.max_call_depth) {
    c.failAt(head.index, "Too many nested subroutine calls (more than " +
                             std::to_string(options_.max_call_depth) + ")");
  }
  const std::string label(head.label);
  LineSource& caller = source();
  const std::uint64_t return_offset = caller.tell();
  const int return_line = caller.lineNumber();
  const SubDef def = findSub(label, c);
  Frame& frame = frames_.emplace_back();
  frame.source = def.source;
  frame.name = label;
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
  const std::string_view what = keywordName(head.keyword);
  if (frames_.size() <= 1) {
    c.failAt(head.index, labelText(head.label) + " " + std::string(what) + " outside a subroutine");
  }
  if (frames_.back().name != head.label) {
    c.failAt(head.index, labelText(head.label) + " " + std::string(what) + " inside subroutine " +
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
  const std::string label(head.label);
  switch (head.keyword) {
    case OKeyword::kIf: {
      const bool condition = readCondition(c, head) != 0.0;
      Control& control = controls.emplace_back();
      control.kind = ControlKind::kIf;
      control.label = label;
      control.line = ref_.line;
      control.taken = condition;
      if (!condition) skipIfBranch(label, control.line);
      return;
    }
    case OKeyword::kElseIf: {
      Control& control = topControl(ControlKind::kIf, head, c);
      if (control.taken) {
        skipTo(label, {OKeyword::kEndIf}, control.line, "if");
        frames_.back().controls.pop_back();
        return;
      }
      if (readCondition(c, head) != 0.0) {
        control.taken = true;
      } else {
        skipIfBranch(label, control.line);
      }
      return;
    }
    case OKeyword::kElse: {
      readTrailingComments(c);
      Control& control = topControl(ControlKind::kIf, head, c);
      if (control.taken) {
        skipTo(label, {OKeyword::kEndIf}, control.line, "if");
        frames_.back().controls.pop_back();
        return;
      }
      control.taken = true;
      return;
    }
    default:  // endif
      readTrailingComments(c);
      topControl(ControlKind::kIf, head, c);
      controls.pop_back();
      return;
  }
}

// Skips a branch not taken: to the next elseif / else (which is then
// handled as usual) or to the endif (which closes the if).
void Reader::skipIfBranch(const std::string& label, int line) {
  const OKeyword stop =
      skipTo(label, {OKeyword::kElseIf, OKeyword::kElse, OKeyword::kEndIf}, line, "if");
  Cursor c(text_, ref_);
  startsWithOWord(c);
  handleOWord(c);
  (void)stop;
}

void Reader::handleWhile(Cursor& c, const OWordHead& head) {
  std::vector<Control>& controls = frames_.back().controls;
  const std::string label(head.label);
  const bool top_matches = !controls.empty() && controls.back().label == label;
  if (head.keyword == OKeyword::kDo) {
    readTrailingComments(c);
    Control& control = controls.emplace_back();
    control.kind = ControlKind::kDo;
    control.label = label;
    control.offset = source().tell();
    control.line = ref_.line;
    return;
  }
  if (head.keyword == OKeyword::kRepeat) {
    const double count = readCondition(c, head);
    const int line = ref_.line;
    if (!(count >= 1.0)) {  // also NaN
      skipTo(label, {OKeyword::kEndRepeat}, line, "repeat");
      return;
    }
    Control& control = controls.emplace_back();
    control.kind = ControlKind::kRepeat;
    control.label = label;
    control.offset = source().tell();
    control.line = line;
    control.remaining = count >= 1e18 ? ~std::uint64_t{0} : static_cast<std::uint64_t>(count);
    return;
  }
  // while: the end of a do-while, a loop coming round again, or a new loop.
  const bool condition = readCondition(c, head) != 0.0;
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
      Control& control = controls.emplace_back();
      control.kind = ControlKind::kWhile;
      control.label = label;
      control.offset = line_start_;
      control.line = ref_.line;
    }
    return;
  }
  const int line = ref_.line;
  if (again) controls.pop_back();
  skipTo(label, {OKeyword::kEndWhile}, line, "while");
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

void Reader::countIteration(Control& control) {
  if (++control.iterations >= options_.max_loop_iterations) {
    failLine(control.line, "Loop " + labelText(control.label) + " ran more than " +
                               std::to_string(options_.max_loop_iterations) +
                               " times (endless loop?)");
  }
}

void Reader::handleBreakOrContinue(const OWordHead& head) {
  std::vector<Control>& controls = frames_.back().controls;
  const std::string label(head.label);
  std::size_t i = controls.size();
  while (i > 0 && !(controls[i - 1].label == label && controls[i - 1].kind != ControlKind::kIf))
    --i;
  if (i == 0) {
    failLine(ref_.line, labelText(label) + " " + std::string(keywordName(head.keyword)) +
                            " outside a loop " + labelText(label));
  }
  controls.resize(i);  // leave any if inside the loop
  const Control loop = controls.back();
  const OKeyword end = loop.kind == ControlKind::kWhile ? OKeyword::kEndWhile
                       : loop.kind == ControlKind::kDo  ? OKeyword::kWhile
                                                        : OKeyword::kEndRepeat;
  const std::string_view what = loop.kind == ControlKind::kWhile ? "while"
                                : loop.kind == ControlKind::kDo  ? "do"
                                                                 : "repeat";
  if (head.keyword == OKeyword::kBreak) {
    controls.pop_back();
    skipTo(label, {end}, loop.line, what);
    return;
  }
  if (loop.kind == ControlKind::kWhile) {  // continue: test the condition again
    countIteration(controls.back());
    source().seek(loop.offset);
    source().setLineNumber(loop.line - 1);
    return;
  }
  // do / repeat: go to the loop's end and let it decide.
  skipTo(label, {end}, loop.line, what);
  Cursor c(text_, ref_);
  startsWithOWord(c);
  handleOWord(c);
}

OKeyword Reader::skipTo(const std::string& label, std::initializer_list<OKeyword> stops,
                        int from_line, std::string_view what) {
  const int source_index = frames_.back().source;
  while (readLine(source_index)) {
    if (isClosingPercent()) break;
    Cursor c(text_, ref_);
    if (!startsWithOWord(c)) continue;
    const OWordHead head = readOWordHead(c);
    if (head.label != label) continue;
    for (OKeyword stop : stops) {
      if (head.keyword == stop) return stop;
    }
  }
  std::string wanted;
  for (OKeyword stop : stops) {
    if (!wanted.empty()) wanted += " / ";
    wanted += std::string(keywordName(stop));
  }
  failLine(from_line, labelText(label) + " " + std::string(what) + " has no matching " + wanted);
}

}  // namespace mdhd::gcode

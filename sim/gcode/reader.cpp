#include "sim/gcode/reader.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>

namespace mdhd::gcode {
namespace {

// Letters that make words: A..Z without N and O (those are the reader's),
// plus LinuxCNC's '$' (spindle select, e.g. `M3 $0 S1`) and its polar
// coordinates '@' (radius) and '^' (angle).
constexpr std::array<bool, 256> makeWordLetters() {
  std::array<bool, 256> table{};
  for (char c : std::string_view("abcdefghijklmpqrstuvwxyz$@^"))
    table[static_cast<unsigned char>(c)] = true;
  return table;
}
constexpr std::array<bool, 256> kWordLetter = makeWordLetters();

char upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}

// Case-insensitive "starts with" for comment keywords such as "msg,".
bool startsWithNoCase(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    char c = text[i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != prefix[i]) return false;
  }
  return true;
}

}  // namespace

SubroutineLoader makeDirectoryLoader(std::vector<std::string> directories) {
  return
      [directories = std::move(directories)](std::string_view name) -> std::unique_ptr<LineSource> {
        for (const std::string& dir : directories) {
          std::string path = dir;
          if (!path.empty() && path.back() != '/') path += '/';
          path.append(name).append(".ngc");
          auto file = std::make_unique<std::ifstream>(path, std::ios::binary);
          if (*file) return makeStreamSource(std::move(file));
        }
        return nullptr;
      };
}

Reader::Reader(std::unique_ptr<LineSource> main, ParameterStore& params, SubroutineLoader loader,
               ReaderOptions options)
    : params_(params), loader_(std::move(loader)), options_(options), expressions_(params) {
  sources_.push_back(Source{std::move(main), std::string()});
  frames_.emplace_back();
  ref_.file = &sources_.front().file;
}

Reader::~Reader() = default;

bool Reader::next(Block& out) {
  while (!ended_) {
    if (!readLine(frames_.back().source)) {
      if (frames_.size() > 1) {
        failLine(source().lineNumber(), 1,
                 "End of file inside subroutine o<" + frames_.back().name + ">: endsub missing");
      }
      ended_ = true;
      break;
    }
    if (processLine(out)) return true;
  }
  return false;
}

void Reader::failLine(int line, int column, const std::string& message) const {
  throw GcodeError({*ref_.file, line, column}, message);
}

bool Reader::readLine(int source_index) {
  Source& src = sources_[static_cast<std::size_t>(source_index)];
  ref_.file = &src.file;
  line_start_ = src.lines->tell();
  bool got = false;
  try {
    got = src.lines->getLine(raw_);
  } catch (const GcodeError& e) {
    throw GcodeError({src.file, e.line(), e.column()}, e.what());
  }
  if (!got) return false;
  if (options_.each_line) options_.each_line();
  ref_.line = src.lines->lineNumber();
  if (++steps_ > options_.max_steps) {
    failLine(ref_.line, 1,
             "Program exceeds the limit of " + std::to_string(options_.max_steps) +
                 " lines read (endless loop?)");
  }
  normalizeLine(raw_, text_, ref_);
  return true;
}

// LinuxCNC: a program whose first line starts with '%' ends at a line that
// is only '%'; nothing after it is read.
bool Reader::isClosingPercent() const {
  return percent_opened_ && frames_.back().source == 0 && text_.code == "%";
}

bool Reader::processLine(Block& out) {
  Cursor c(text_, ref_);
  if (c.atEnd()) return false;
  if (c.peek() == '%') {
    if (ref_.line == 1 && frames_.back().source == 0 && line_start_ == 0) {
      percent_opened_ = true;  // the opening tape mark (the rest of the line is ignored)
      return false;
    }
    if (isClosingPercent()) {
      ended_ = true;
      ended_at_percent_ = true;
      return false;
    }
  }
  if (c.peek() == '/') {
    if (options_.block_delete) return false;
    c.advance();
  }
  out.has_n = false;
  out.n = 0.0;
  if (c.peek() == 'n') {
    c.advance();
    out.has_n = true;
    out.n = c.readLineNumber();
  }
  if (c.peek() == 'o') {
    handleOWord(c);
    return false;
  }
  parseBlock(c, out);
  return !out.words.empty() || !out.comments.empty() || out.has_n;
}

void Reader::parseBlock(Cursor& c, Block& out) {
  out.words.clear();
  out.comments.clear();
  out.messages.clear();
  out.prints.clear();
  comment_columns_.clear();
  assignment_count_ = 0;
  while (!c.atEnd()) {
    const char ch = c.peek();
    if (kWordLetter[static_cast<unsigned char>(ch)]) {
      Word& word = out.words.emplace_back();
      word.letter = upper(ch);
      word.column = c.column();
      c.advance();
      word.value = expressions_.readRealValue(c);
    } else if (ch == '(') {
      comment_columns_.push_back(c.column());
      std::string_view text = c.readComment();
      // LinuxCNC passes comments on without their leading blanks.
      while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
      out.comments.emplace_back(text);
    } else if (ch == '#') {
      readAssignment(c);
    } else {  // includes N and O words not at the start, as LinuxCNC
      c.fail(badCharacterMessage(ch));
    }
  }
  applyAssignments();
  if (!out.comments.empty()) handleComments(out);
  out.pos.file = *ref_.file;
  out.pos.line = ref_.line;
  out.pos.column = out.words.empty() ? 1 : out.words.front().column;  // the block's place
  out.text = raw_;
}

void Reader::readAssignment(Cursor& c) {
  const ParameterRef ref = expressions_.readParameterRef(c);
  if (c.peek() != '=') c.fail("Equal sign missing in parameter setting");
  c.advance();
  const double value = expressions_.readRealValue(c);
  if (ref.named && params_.isReadOnly(ref.name)) {
    c.failAt(ref.index, "Cannot assign to read-only parameter #<" + std::string(ref.name) + ">");
  }
  if (assignment_count_ == assignments_.size()) assignments_.emplace_back();
  Assignment& a = assignments_[assignment_count_++];
  a.named = ref.named;
  a.number = ref.number;
  a.name.assign(ref.name);
  a.value = value;
}

// LinuxCNC semantics: every value on a line is read with the parameters as
// they were before the line; the line's settings take effect together after.
void Reader::applyAssignments() {
  for (std::size_t i = 0; i < assignment_count_; ++i) {
    const Assignment& a = assignments_[i];
    if (a.named) {
      params_.setNamed(a.name, a.value);
    } else {
      params_.set(a.number, a.value);
    }
  }
  assignment_count_ = 0;
}

// LinuxCNC keeps only the last comment of a line as the block's comment, so
// only that one can be a message; all of them stay in Block::comments.
void Reader::handleComments(Block& out) {
  const std::string_view text = out.comments.back();
  const int column = comment_columns_.back();
  if (startsWithNoCase(text, "msg,")) {
    out.messages.emplace_back(text.substr(4));
  } else if (startsWithNoCase(text, "debug,")) {
    std::string expanded = substituteParameters(text.substr(6), column);
    if (params_.get(ParameterStore::kDebugEnable) > 0.0)
      out.messages.push_back(std::move(expanded));
  } else if (startsWithNoCase(text, "print,")) {
    out.prints.push_back(substituteParameters(text.substr(6), column));
  } else if (startsWithNoCase(text, "abort,")) {
    // LinuxCNC stops the program with the expanded text as the error.
    throw GcodeError({*ref_.file, ref_.line, column}, substituteParameters(text.substr(6), column));
  }
}

// (DEBUG,...) / (PRINT,...) as LinuxCNC expands them: #<name> and #number
// become the value printed "%lf"; an unknown one becomes "######".
std::string Reader::substituteParameters(std::string_view text, int column) {
  const auto fail = [&] {
    throw GcodeError({*ref_.file, ref_.line, column}, "Named parameter not terminated");
  };
  std::string result;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] != '#') {
      result.push_back(text[i++]);
      continue;
    }
    ++i;
    if (i == text.size()) fail();
    std::optional<double> value;
    if (text[i] >= '0' && text[i] <= '9') {
      long index = 0;
      while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
        if (index <= ParameterStore::kMaxNumber) index = index * 10 + (text[i] - '0');
        ++i;
      }
      if (index == 0) value = 0.0;  // LinuxCNC's unused slot #0
      if (ParameterStore::validNumber(static_cast<int>(index))) {
        value = params_.get(static_cast<int>(index));
      }
    } else if (text[i] == '<') {
      const std::size_t close = text.find('>', i);
      if (close == std::string_view::npos) fail();
      std::string name;
      for (char ch : text.substr(i + 1, close - i - 1)) {
        if (ch == ' ' || ch == '\t') continue;
        name.push_back((ch >= 'A' && ch <= 'Z') ? static_cast<char>(ch - 'A' + 'a') : ch);
      }
      value = params_.findNamed(name);
      i = close + 1;
    } else {
      result.push_back('#');
      continue;
    }
    char number[32];
    const double v = (value && std::fabs(*value) < 0.0001) ? 0.0 : value.value_or(0.0);
    const int n = std::snprintf(number, sizeof number, "%f", v);
    result.append(value && n > 0 && n < 30 ? number : "######");
  }
  return result;
}

}  // namespace mdhd::gcode

#include "sim/gcode/reader.h"

#include <array>
#include <cstdio>
#include <fstream>
#include <utility>

namespace mdhd::gcode {
namespace {

// Letters that make words: A..Z without E, N and O (N and O are the
// reader's), plus LinuxCNC's '$' (spindle select, e.g. `M3 $0 S1`).
constexpr std::array<bool, 256> makeWordLetters() {
  std::array<bool, 256> table{};
  for (char c : std::string_view("abcdfghijklmpqrstuvwxyz$"))
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
        failLine(source().lineNumber(),
                 "End of file inside subroutine o<" + frames_.back().name + ">: endsub missing");
      }
      ended_ = true;
      break;
    }
    if (processLine(out)) return true;
  }
  return false;
}

void Reader::failLine(int line, const std::string& message) const {
  throw GcodeError({*ref_.file, line, 0}, message);
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
  ref_.line = src.lines->lineNumber();
  if (++steps_ > options_.max_steps) {
    failLine(ref_.line, "Program exceeds the limit of " + std::to_string(options_.max_steps) +
                            " lines read (endless loop?)");
  }
  normalizeLine(raw_, text_, ref_);
  return true;
}

bool Reader::isClosingPercent() {
  return frames_.back().source == 0 && percents_ > 0 && !text_.code.empty() &&
         text_.code.front() == '%';
}

bool Reader::processLine(Block& out) {
  Cursor c(text_, ref_);
  if (c.atEnd()) return false;
  if (c.peek() == '%') {
    // First '%' opens the program (tape mark), the next one ends it.
    if (frames_.back().source == 0 && ++percents_ >= 2) ended_ = true;
    return false;
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
    out.n = c.readUnsignedNumber();
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
    } else if (ch == 'n') {
      c.fail("N word (line number) must come first on the line");
    } else if (ch == 'o') {
      c.fail("O-word must come first on the line");
    } else {
      c.fail(badCharacterMessage(ch));
    }
  }
  applyAssignments();
  if (!out.comments.empty()) handleComments(out);
  out.pos.file = *ref_.file;
  out.pos.line = ref_.line;
  out.pos.column = 0;
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

void Reader::handleComments(Block& out) {
  for (std::size_t i = 0; i < out.comments.size(); ++i) {
    const std::string_view text = out.comments[i];
    const int column = comment_columns_[i];
    if (startsWithNoCase(text, "msg,")) {
      out.messages.emplace_back(text.substr(4));
    } else if (startsWithNoCase(text, "debug,")) {
      out.messages.push_back(substituteParameters(text.substr(6), column));
    } else if (startsWithNoCase(text, "print,")) {
      out.prints.push_back(substituteParameters(text.substr(6), column));
    }
  }
}

// (DEBUG,...) / (PRINT,...): #<name> and #number are replaced by their value
// printed as LinuxCNC does ("%lf").
std::string Reader::substituteParameters(std::string_view text, int column) {
  std::string result;
  char number[64];
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c != '#') {
      result.push_back(c);
      ++i;
      continue;
    }
    double value = 0.0;
    std::size_t end = i + 1;
    if (end < text.size() && text[end] == '<') {
      const std::size_t close = text.find('>', end);
      if (close == std::string_view::npos) {
        result.append(text.substr(i));
        break;
      }
      std::string name;
      for (char ch : text.substr(end + 1, close - end - 1)) {
        if (ch == ' ' || ch == '\t') continue;
        name.push_back((ch >= 'A' && ch <= 'Z') ? static_cast<char>(ch - 'A' + 'a') : ch);
      }
      const auto found = params_.findNamed(name);
      if (!found) {
        throw GcodeError({*ref_.file, ref_.line, column},
                         "Named parameter #<" + name + "> not defined");
      }
      value = *found;
      end = close + 1;
    } else {
      int index = 0;
      while (end < text.size() && text[end] >= '0' && text[end] <= '9' && index <= 99999) {
        index = index * 10 + (text[end] - '0');
        ++end;
      }
      if (end == i + 1 || !ParameterStore::validNumber(index)) {
        result.push_back(c);
        ++i;
        continue;
      }
      value = params_.get(index);
    }
    std::snprintf(number, sizeof number, "%f", value);
    result.append(number);
    i = end;
  }
  return result;
}

}  // namespace mdhd::gcode

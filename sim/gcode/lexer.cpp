#include "sim/gcode/lexer.h"

#include <charconv>
#include <cstdio>

namespace mdhd::gcode {
namespace {

// LinuxCNC drops spaces, tabs and carriage returns outside comments.
bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}
bool isDigit(char c) {
  return c >= '0' && c <= '9';
}
// How many continuation bytes follow a UTF-8 lead byte at raw[i]; 0 when they do not
// all follow (not UTF-8: the lead is a character of its own).
int utf8Continuations(std::string_view raw, std::size_t i) {
  const auto u = static_cast<unsigned char>(raw[i]);
  const int n = (u & 0xE0) == 0xC0 ? 1 : (u & 0xF0) == 0xE0 ? 2 : (u & 0xF8) == 0xF0 ? 3 : 0;
  if (i + static_cast<std::size_t>(n) >= raw.size()) return 0;
  for (int k = 1; k <= n; ++k)
    if ((static_cast<unsigned char>(raw[i + k]) & 0xC0) != 0x80) return 0;
  return n;
}

char lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

}  // namespace

void normalizeLine(std::string_view raw, LineText& out, const LineRef& ref) {
  // Written through raw pointers into buffers sized for the whole line, then
  // trimmed: this runs once per line and is the reader's hottest loop.
  out.code.resize(raw.size());
  out.columns.resize(raw.size());
  char* code = out.code.data();
  int* columns = out.columns.data();
  std::size_t n = 0;
  int column = 0;         // in characters: a UTF-8 sequence is one column
  int pending = 0;        // continuation bytes left of the current UTF-8 sequence
  int comment_start = 0;  // column of the open '(' (0: not in a comment)
  out.end_column = 0;     // 0: not cut short by ';'
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const char c = raw[i];
    // A whole UTF-8 sequence is one column; any other byte (Latin-1) is one too.
    const auto u = static_cast<unsigned char>(c);
    if (pending > 0) {
      --pending;
    } else {
      ++column;
      if (u >= 0xC0) pending = utf8Continuations(raw, i);
    }
    if (comment_start != 0) {
      if (c == '(') throw GcodeError(ref.at(column), "Nested comment found");
      if (c == ')') comment_start = 0;
    } else if (isBlank(c)) {
      continue;
    } else if (c == ';') {
      out.end_column = column;
      break;
    } else if (c == '(') {
      comment_start = column;
    }
    code[n] = comment_start != 0 || c == ')' ? c : lower(c);
    columns[n] = column;
    ++n;
  }
  if (out.end_column == 0) out.end_column = column + 1;
  out.code.resize(n);
  out.columns.resize(n);
  if (comment_start != 0) throw GcodeError(ref.at(comment_start), "Unclosed comment found");
}

bool Cursor::accept(std::string_view word) {
  if (rest().substr(0, word.size()) != word) return false;
  index_ += word.size();
  return true;
}

void Cursor::failAt(std::size_t index, const std::string& message) const {
  throw GcodeError(ref_.at(columnAt(index)), message);
}

double Cursor::readUnsignedNumber() {
  const std::string& code = text_.code;
  const std::size_t start = index_;
  std::size_t i = start;
  std::size_t digits = 0;
  std::size_t points = 0;
  std::size_t first_end = std::string::npos;  // end of the part before a second point
  while (i < code.size() && (isDigit(code[i]) || code[i] == '.')) {
    if (code[i] == '.' && ++points == 2) first_end = i;
    if (isDigit(code[i])) ++digits;
    ++i;
  }
  const std::string_view span = std::string_view(code).substr(start, i - start);
  if (digits == 0) {
    failAt(start, "bad number format (conversion failed) parsing '" + std::string(span) + "'");
  }
  if (first_end != std::string::npos) {
    failAt(start, "bad number format (trailing characters) parsing '" + std::string(span) + "'");
  }
  double value = 0.0;
  const auto result = std::from_chars(code.data() + start, code.data() + i, value);
  if (result.ec != std::errc() || result.ptr != code.data() + i) {
    failAt(start, "bad number format (conversion failed) parsing '" + std::string(span) + "'");
  }
  index_ = i;
  return value;
}

double Cursor::readLineNumber() {
  const std::string& code = text_.code;
  const std::size_t start = index_;
  std::size_t i = start;
  while (i < code.size() && isDigit(code[i])) ++i;
  if (i == start) failAt(start, "Bad format unsigned integer");
  if (i < code.size() && code[i] == '.') {
    const std::size_t fraction = ++i;
    while (i < code.size() && isDigit(code[i])) ++i;
    if (i == fraction) failAt(fraction, "Bad format unsigned integer");
  }
  double value = 0.0;
  std::from_chars(code.data() + start, code.data() + i, value);
  index_ = i;
  return value;
}

std::string_view Cursor::readComment() {
  const std::size_t open = index_;
  const std::size_t close = text_.code.find(')', open);
  if (close == std::string::npos) failAt(open, "Unclosed comment found");
  index_ = close + 1;
  return std::string_view(text_.code).substr(open + 1, close - open - 1);
}

// As LinuxCNC: printable characters quoted, others (and anything past 'z')
// as a three-digit octal escape.
std::string badCharacterMessage(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u > ' ' && u <= 'z') return std::string("Bad character '") + c + "' used";
  char octal[8];
  std::snprintf(octal, sizeof octal, "\\%03o", static_cast<unsigned>(u));
  return std::string("Bad character '") + octal + "' used";
}

}  // namespace mdhd::gcode

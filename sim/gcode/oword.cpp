#include "sim/gcode/oword.h"

#include <array>
#include <string>

namespace mdhd::gcode {
namespace {

struct KeywordName {
  std::string_view text;
  OKeyword keyword;
};
constexpr std::array<KeywordName, 15> kKeywords{{
    {"sub", OKeyword::kSub},
    {"endsub", OKeyword::kEndSub},
    {"call", OKeyword::kCall},
    {"return", OKeyword::kReturn},
    {"if", OKeyword::kIf},
    {"elseif", OKeyword::kElseIf},
    {"else", OKeyword::kElse},
    {"endif", OKeyword::kEndIf},
    {"while", OKeyword::kWhile},
    {"endwhile", OKeyword::kEndWhile},
    {"do", OKeyword::kDo},
    {"break", OKeyword::kBreak},
    {"continue", OKeyword::kContinue},
    {"repeat", OKeyword::kRepeat},
    {"endrepeat", OKeyword::kEndRepeat},
}};

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}
bool isLetter(char c) {
  return c >= 'a' && c <= 'z';
}

}  // namespace

std::string_view keywordName(OKeyword keyword) {
  for (const KeywordName& k : kKeywords) {
    if (k.keyword == keyword) return k.text;
  }
  return "?";
}

bool startsWithOWord(Cursor& c) {
  if (c.peek() == '/') c.advance();
  if (c.peek() == 'n') {
    c.advance();
    while (isDigit(c.peek()) || c.peek() == '.') c.advance();
  }
  return c.peek() == 'o';
}

OWordHead readOWordHead(Cursor& c) {
  OWordHead head;
  head.index = c.index();
  c.advance();  // 'o'
  const std::string_view rest = c.rest();
  if (c.peek() == '<') {
    const std::size_t close = rest.find('>');
    if (close == std::string_view::npos) c.fail("O-word name not terminated by '>'");
    if (close == 1) c.fail("O-word name is empty");
    head.label = rest.substr(1, close - 1);
    c.advance(close + 1);
  } else {
    std::size_t n = 0;
    while (n < rest.size() && isDigit(rest[n])) ++n;
    if (n == 0) c.fail("Bad O-word label: a number or <name> must follow 'O'");
    std::size_t first = 0;
    while (first + 1 < n && rest[first] == '0') ++first;
    head.label = rest.substr(first, n - first);
    c.advance(n);
  }
  const std::string_view after = c.rest();
  std::size_t n = 0;
  while (n < after.size() && isLetter(after[n])) ++n;
  const std::string_view word = after.substr(0, n);
  for (const KeywordName& k : kKeywords) {
    if (k.text == word) {
      head.keyword = k.keyword;
      c.advance(n);
      return head;
    }
  }
  if (n == 0) c.fail("O-word without a command (sub, call, if, while, ...)");
  c.fail("Unknown O-word command '" + std::string(word) + "'");
}

}  // namespace mdhd::gcode

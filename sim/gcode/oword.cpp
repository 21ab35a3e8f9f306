#include "sim/gcode/oword.h"

#include <array>
#include <string>

namespace mdhd::gcode {
namespace {

struct KeywordName {
  std::string_view text;
  OKeyword keyword;
};
// In LinuxCNC's matching order: each is tried as a prefix, so "elseif" must
// come before "else".
constexpr std::array<KeywordName, 15> kKeywords{{
    {"sub", OKeyword::kSub},
    {"endsub", OKeyword::kEndSub},
    {"call", OKeyword::kCall},
    {"do", OKeyword::kDo},
    {"while", OKeyword::kWhile},
    {"repeat", OKeyword::kRepeat},
    {"if", OKeyword::kIf},
    {"elseif", OKeyword::kElseIf},
    {"else", OKeyword::kElse},
    {"endif", OKeyword::kEndIf},
    {"break", OKeyword::kBreak},
    {"continue", OKeyword::kContinue},
    {"endwhile", OKeyword::kEndWhile},
    {"endrepeat", OKeyword::kEndRepeat},
    {"return", OKeyword::kReturn},
}};

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

}  // namespace

std::string_view keywordName(OKeyword keyword) {
  for (const KeywordName& k : kKeywords) {
    if (k.keyword == keyword) return k.text;
  }
  return "";
}

bool startsWithOWord(Cursor& c) {
  if (c.peek() == '/') c.advance();
  if (c.peek() == 'n') {
    c.advance();
    while (isDigit(c.peek()) || c.peek() == '.') c.advance();
  }
  return c.peek() == 'o';
}

OWordHead readOWordHead(Cursor& c, ExpressionReader& expressions) {
  OWordHead head;
  head.index = c.index();
  c.advance();  // 'o'
  if (c.peek() == '<') {
    const std::string_view rest = c.rest();
    const std::size_t close = rest.find('>');
    if (close == std::string_view::npos) c.fail("Named parameter not terminated");
    head.label.assign(rest.substr(1, close - 1));
    c.advance(close + 1);
  } else {
    head.label = std::to_string(expressions.readIntegerValue(c));
  }
  const std::string_view after = c.rest();
  if (after.empty() || after.front() == '(') {
    head.keyword = OKeyword::kProgramNumber;
    return head;
  }
  for (const KeywordName& k : kKeywords) {
    if (after.substr(0, k.text.size()) == k.text) {
      head.keyword = k.keyword;
      c.advance(k.text.size());
      return head;
    }
  }
  c.fail("Unknown command in O line");
}

}  // namespace mdhd::gcode

#include "sim/gcode/lexer.h"

#include <gtest/gtest.h>

namespace mdhd::gcode {
namespace {

const std::string kFile = "prog.ngc";

LineText normalize(std::string_view raw) {
  LineText text;
  normalizeLine(raw, text, LineRef{&kFile, 7});
  return text;
}

TEST(Lexer, RemovesBlanksAndLowersOutsideComments) {
  const LineText t = normalize("G 0 X 1 . 5\tY-2 (Keep This ) Z3");
  EXPECT_EQ(t.code, "g0x1.5y-2(Keep This )z3");
  // Columns point at the raw characters.
  EXPECT_EQ(t.columns[0], 1);  // G
  EXPECT_EQ(t.columns[1], 3);  // 0
  EXPECT_EQ(t.columns[2], 5);  // X
  EXPECT_EQ(t.columns[4], 9);  // .
  EXPECT_EQ(t.end_column, 32);
}

TEST(Lexer, CarriageReturnIsABlank) {
  EXPECT_EQ(normalize("G0\rX1 (a\rb)").code, "g0x1(a\rb)");
}

TEST(Lexer, SemicolonEndsTheLine) {
  const LineText t = normalize("G1 X2 ; (not a comment ( at all");
  EXPECT_EQ(t.code, "g1x2");
  EXPECT_EQ(t.end_column, 7);
}

TEST(Lexer, NestedCommentIsAnErrorAtTheInnerParenthesis) {
  try {
    normalize("G0 (outer (inner) )");
    FAIL();
  } catch (const GcodeError& e) {
    EXPECT_STREQ(e.what(), "Nested comment found");
    EXPECT_EQ(e.pos().file, "prog.ngc");
    EXPECT_EQ(e.line(), 7);
    EXPECT_EQ(e.column(), 11);
  }
}

TEST(Lexer, UnclosedCommentIsAnErrorAtItsStart) {
  try {
    normalize("G0 X1 (open");
    FAIL();
  } catch (const GcodeError& e) {
    EXPECT_STREQ(e.what(), "Unclosed comment found");
    EXPECT_EQ(e.column(), 7);
  }
}

double number(std::string_view raw, std::size_t* consumed = nullptr) {
  const LineText t = normalize(raw);
  const std::string file;
  LineRef ref{&file, 1};
  Cursor c(t, ref);
  const double v = c.readUnsignedNumber();
  if (consumed) *consumed = c.index();
  return v;
}

TEST(Lexer, NumbersAreCorrectlyRounded) {
  EXPECT_EQ(number("12.345"), 12.345);
  EXPECT_EQ(number("1."), 1.0);
  EXPECT_EQ(number(".5"), 0.5);
  EXPECT_EQ(number("0.1"), 0.1);
  EXPECT_EQ(number("1 2 . 3 4 5"), 12.345);
  EXPECT_EQ(number("000123"), 123.0);
  EXPECT_EQ(number("2.2250738585072014"), 2.2250738585072014);
  std::size_t used = 0;
  EXPECT_EQ(number("1.5e3", &used), 1.5);  // no exponents in G-code: 'e' is not part of it
  EXPECT_EQ(used, 3u);
}

TEST(Lexer, MissingDigitsIsAnError) {
  try {
    number(".x");
    FAIL();
  } catch (const GcodeError& e) {
    EXPECT_STREQ(e.what(), "bad number format (conversion failed) parsing '.'");
    EXPECT_EQ(e.column(), 1);
  }
}

TEST(Lexer, NumberFormatErrorsAsLinuxCnc) {
  try {
    number("1.2.3");
    FAIL();
  } catch (const GcodeError& e) {
    EXPECT_STREQ(e.what(), "bad number format (trailing characters) parsing '1.2.3'");
  }
}

TEST(Lexer, CommentTextIsVerbatim) {
  const LineText t = normalize("(MSG, Hello World)x1");
  const std::string file;
  LineRef ref{&file, 1};
  Cursor c(t, ref);
  EXPECT_EQ(c.readComment(), "MSG, Hello World");
  EXPECT_EQ(c.peek(), 'x');
}

TEST(Lexer, BadCharacterMessages) {
  EXPECT_EQ(badCharacterMessage('u'), "Bad character 'u' used");
  EXPECT_EQ(badCharacterMessage('\x01'), "Bad character '\\001' used");
  EXPECT_EQ(badCharacterMessage('{'), "Bad character '\\173' used");
}

}  // namespace
}  // namespace mdhd::gcode

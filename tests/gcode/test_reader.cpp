#include "sim/gcode/reader.h"

#include <gtest/gtest.h>

#include <sstream>

#include "tests/gcode/test_reader_helpers.h"

namespace mdhd::gcode {
namespace {

using testing::readAll;
using testing::readError;
using testing::values;
using testing::wordValue;

TEST(Reader, WordsWithValuesColumnsAndPositions) {
  const auto blocks = readAll("G1 X12.345 Y-6.789 Z-1.5 F800\n\ng0x1y2\n");
  ASSERT_EQ(blocks.size(), 2u);
  const Block& b = blocks[0];
  ASSERT_EQ(b.words.size(), 5u);
  EXPECT_EQ(b.words[0].letter, 'G');
  EXPECT_EQ(b.words[0].value, 1.0);
  EXPECT_EQ(b.words[0].column, 1);
  EXPECT_EQ(b.words[1].letter, 'X');
  EXPECT_EQ(b.words[1].value, 12.345);
  EXPECT_EQ(b.words[1].column, 4);
  EXPECT_EQ(b.words[2].value, -6.789);
  EXPECT_EQ(b.words[3].value, -1.5);
  EXPECT_EQ(b.words[4].letter, 'F');
  EXPECT_EQ(b.words[4].value, 800.0);
  EXPECT_EQ(b.pos.line, 1);
  EXPECT_EQ(b.pos.file, "");
  EXPECT_EQ(b.text, "G1 X12.345 Y-6.789 Z-1.5 F800");
  EXPECT_EQ(blocks[1].pos.line, 3);  // the blank line 2 gives no block
  EXPECT_EQ(blocks[1].words[1].letter, 'X');
}

TEST(Reader, OddSpacingAndCase) {
  const auto blocks = readAll("g 0 x 1 . 5 Y\t-.5 z+2 G 90 . 1\n");
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(wordValue(blocks[0], 'X'), 1.5);
  EXPECT_EQ(wordValue(blocks[0], 'Y'), -0.5);
  EXPECT_EQ(wordValue(blocks[0], 'Z'), 2.0);
  EXPECT_EQ(blocks[0].words[4].value, 90.1);
  EXPECT_EQ(blocks[0].words[2].column, 13);
}

TEST(Reader, AllWordLettersAndDollar) {
  const auto blocks = readAll(
      "A1 B2 C3 D4 E4.5 F5 G6 H7 I8 J9 K10 L11 M12 P13 Q14 R15 S16 T17 U18 V19 W20 "
      "X21 Y22 Z23 $0\n");
  ASSERT_EQ(blocks.size(), 1u);
  const std::string letters = "ABCDEFGHIJKLMPQRSTUVWXYZ$";
  ASSERT_EQ(blocks[0].words.size(), letters.size());
  for (std::size_t i = 0; i < letters.size(); ++i) {
    EXPECT_EQ(blocks[0].words[i].letter, letters[i]);
  }
  EXPECT_EQ(blocks[0].words.back().value, 0.0);
}

TEST(Reader, LineNumbersAreConsumed) {
  const auto blocks = readAll("N0010 G0 X1\nn20\n");
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_TRUE(blocks[0].has_n);
  EXPECT_EQ(blocks[0].n, 10.0);
  EXPECT_EQ(blocks[0].words.size(), 2u);
  EXPECT_TRUE(blocks[1].has_n);
  EXPECT_EQ(blocks[1].n, 20.0);
  EXPECT_TRUE(blocks[1].words.empty());
}

TEST(Reader, CommentsAndMessages) {
  ParameterStore params;
  const auto blocks = readAll(
      "G0 (first) X1 (second) ; rest ignored (even this\n"
      "(MSG,Change tool now)\n"
      "( msg, spaced)\n"
      "#1 = 2.5 #<depth> = -3 (DEBUG, one=#1 depth=#<Depth> #99999 # x)\n"
      "(PRINT,#1)\n"
      "(debugging is not debug,)\n"
      "(MSG, not this) G0 (MSG, this)\n"
      "#5599 = 0 (DEBUG, switched off)\n",
      params);
  ASSERT_EQ(blocks.size(), 8u);
  EXPECT_EQ(blocks[0].comments, (std::vector<std::string>{"first", "second"}));
  EXPECT_EQ(blocks[0].words.size(), 2u);
  EXPECT_TRUE(blocks[0].messages.empty());
  EXPECT_EQ(blocks[1].messages, std::vector<std::string>{"Change tool now"});
  EXPECT_EQ(blocks[2].messages, std::vector<std::string>{" spaced"});
  // DEBUG sees the line's own assignments (LinuxCNC sets them before executing).
  EXPECT_EQ(blocks[3].messages,
            std::vector<std::string>{" one=2.500000 depth=-3.000000 ###### # x"});
  EXPECT_EQ(blocks[4].prints, std::vector<std::string>{"2.500000"});
  EXPECT_TRUE(blocks[4].messages.empty());
  EXPECT_TRUE(blocks[5].messages.empty());
  // LinuxCNC keeps only the last comment of a line: only it can be a message.
  EXPECT_EQ(blocks[6].messages, std::vector<std::string>{" this"});
  EXPECT_EQ(blocks[6].comments.size(), 2u);
  EXPECT_TRUE(blocks[7].messages.empty());  // #5599 = 0 turns DEBUG off
}

TEST(Reader, DebugParameterSubstitution) {
  const auto blocks = readAll("#3 = -0.00001 (DEBUG, #<missing> #3 #0 #<_value>)\n");
  ASSERT_EQ(blocks.size(), 1u);
  // Unknown names print as LinuxCNC's "######"; near-zero as 0.
  EXPECT_EQ(blocks[0].messages, std::vector<std::string>{" ###### 0.000000 0.000000 0.000000"});
  for (const char* bad : {"G0\n  (DEBUG, #<open)\n", "G0\n  (DEBUG, at end #)\n"}) {
    const GcodeError e = readError(bad);
    EXPECT_STREQ(e.what(), "Named parameter not terminated") << bad;
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), 3);
  }
}

TEST(Reader, AbortCommentStopsWithItsText) {
  const GcodeError e = readError("#1 = 3\nG0 X1 (ABORT,probe failed at #1)\nG0 X2\n");
  EXPECT_STREQ(e.what(), "probe failed at 3.000000");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 7);
}

TEST(Reader, AssignmentsTakeEffectAfterTheLine) {
  const auto blocks = readAll(
      "#1 = 5\n"
      "#1 = 7 G0 X#1 #2 = #1\n"
      "G0 X#1 Y#2\n"
      "#1 = 1 #1 = 2\n"  // the last setting wins
      "X#1\n");
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{5.0, 7.0, 2.0}));
  EXPECT_EQ(wordValue(blocks[1], 'Y'), 5.0);
}

TEST(Reader, IndirectionAndComputedNumbers) {
  const auto blocks = readAll(
      "#1 = 100\n"
      "#100 = 42\n"
      "X##1 #[#1 + 1] = 9\n"
      "Y#101 ##1 = 3\n"
      "Z#100\n");
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(wordValue(blocks[0], 'X'), 42.0);
  EXPECT_EQ(wordValue(blocks[1], 'Y'), 9.0);
  EXPECT_EQ(wordValue(blocks[2], 'Z'), 3.0);
}

TEST(Reader, NamedParametersIgnoreCaseAndBlanks) {
  const auto blocks = readAll("#<My Depth> = 2\nX#<mydepth> Y#<MY DEPTH>\n");
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(wordValue(blocks[0], 'X'), 2.0);
  EXPECT_EQ(wordValue(blocks[0], 'Y'), 2.0);
}

TEST(Reader, PredefinedNamedParametersComeFromTheHook) {
  ParameterStore params;
  params.setPredefined([](std::string_view name) -> std::optional<double> {
    if (name == "_x") return 12.5;
    return std::nullopt;
  });
  const auto blocks = testing::readAll("G0 X[#<_x> + 1]\n", params);
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(wordValue(blocks[0], 'X'), 13.5);
  try {
    testing::readAll("G0\n  #<_x> = 3\n", params);
    FAIL();
  } catch (const GcodeError& e) {
    EXPECT_STREQ(e.what(), "Cannot assign to read-only parameter #<_x>");
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), 3);
  }
}

TEST(Reader, TheInterpreterSeesAssignmentsInTheStore) {
  ParameterStore params;
  testing::readAll("#5221 = -10 #<_global> = 4\n", params);
  EXPECT_EQ(params.get(5221), -10.0);
  EXPECT_EQ(params.findNamed("_global").value(), 4.0);
}

TEST(Reader, PercentMarksTheProgramsEnds) {
  const auto blocks = readAll("%\nG0 X1\n%\nG0 X2\n");
  EXPECT_EQ(values(blocks, 'X'), std::vector<double>{1.0});
  const auto spaced = readAll(" % tape\nG0 X1\n  %  \nG0 X2\n");
  EXPECT_EQ(values(spaced, 'X'), std::vector<double>{1.0});
  EXPECT_STREQ(readError("%\nG0 X1\n%5\n").what(), "Bad character '%' used");
  for (const auto& [program, closed] : {std::pair{"%\nG0\n%\n", true}, {"%\nG0\n", false}}) {
    ParameterStore params;
    Reader reader(makeStringSource(program), params);
    Block block;
    while (reader.next(block)) {
    }
    EXPECT_TRUE(reader.startedWithPercent());
    EXPECT_EQ(reader.endedAtPercent(), closed);
  }
  const auto no_marks = readAll("G0 X1\nG0 X2\n");
  EXPECT_EQ(values(no_marks, 'X'), (std::vector<double>{1.0, 2.0}));
}

TEST(Reader, BlockDeleteIsAnOption) {
  const std::string program = "G0 X1\n/G0 X2\n  / G0 X3\n";
  EXPECT_EQ(values(readAll(program), 'X'), (std::vector<double>{1.0, 2.0, 3.0}));
  ReaderOptions on;
  on.block_delete = true;
  EXPECT_EQ(values(readAll(program, on), 'X'), std::vector<double>{1.0});
}

TEST(Reader, CarriageReturnsAreStripped) {
  const auto blocks = readAll("G0 X1\r\nG0 X2\r\n");
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].text, "G0 X1");
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{1.0, 2.0}));
}

TEST(Reader, ErrorsNameLineAndColumn) {
  struct Case {
    const char* program;
    const char* message;
    int line;
    int column;
  } cases[] = {
      {"G0\nG1 {5\n", "Bad character '\\173' used", 2, 4},
      {"G0\nG1 X1 * 2\n", "Bad character '*' used", 2, 7},
      {"G1 X1 N5\n", "Bad character 'n' used", 1, 7},
      {"G1 o100 call\n", "Bad character 'o' used", 1, 4},
      {"G0\n%\n", "Bad character '%' used", 2, 1},  // '%' opens only on line 1
      {"N\n", "Bad format unsigned integer", 1, 2},
      {"\n\n  G0 (a (b))\n", "Nested comment found", 3, 9},
      {"G0 (open\n", "Unclosed comment found", 1, 4},
      {"#1 X5\n", "Equal sign missing in parameter setting", 1, 4},
      {"#<a = 5\n", "Named parameter not terminated", 1, 2},
      {"G0 X@\n", "bad number format (conversion failed) parsing ''", 1, 5},
      // Columns count characters: UTF-8 sequences are one, so are Latin-1 bytes.
      {"(\xc3\xa9\xe2\x82\xac) G1 X1 * 2\n", "Bad character '*' used", 1, 12},
      {"(\xe9\xb0) G1 X1 * 2\n", "Bad character '*' used", 1, 12},
      {"(\xb0) G1 X1 * 2\n", "Bad character '*' used", 1, 11},
  };
  for (const Case& c : cases) {
    const GcodeError e = readError(c.program);
    EXPECT_EQ(std::string(e.what()), c.message) << c.program;
    EXPECT_EQ(e.line(), c.line) << c.program;
    EXPECT_EQ(e.column(), c.column) << c.program;
  }
}

TEST(Reader, StreamSourceGivesTheSameBlocks) {
  const std::string program = "G0 X1\n#1=2\nG1 X#1 F100\n(c)\n";
  ParameterStore params;
  Reader reader(makeStreamSource(std::make_unique<std::istringstream>(program)), params);
  Block block;
  std::vector<Block> blocks;
  while (reader.next(block)) blocks.push_back(block);
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(blocks[2].pos.line, 4);
}

}  // namespace
}  // namespace mdhd::gcode

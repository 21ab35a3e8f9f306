// O-word labels as LinuxCNC 2.9 keeps them: one if / while / do / repeat line per
// label in the program and in each subroutine (rs274 "duplicate O-word label").
// The oracle programs 24 and 99 hold rs274's traces of the same rules.
#include <gtest/gtest.h>

#include "tests/gcode/test_reader_helpers.h"

namespace mdhd::gcode {
namespace {

using testing::readAll;
using testing::readError;
using testing::values;

TEST(OWordLabels, ASecondIfOfOneLabelIsAnErrorAtItsLineAndColumn) {
  const GcodeError e = readError(
      "G0 X0\n"
      "o1 if [1]\n"
      "  G0 X1\n"
      "o1 endif\n"
      "  o1 if [1]\n"
      "  G0 X2\n"
      "o1 endif\n");
  EXPECT_EQ(e.line(), 5);
  EXPECT_EQ(e.column(), 3);
  EXPECT_NE(std::string(e.what()).find("Duplicate O-word label o<1>"), std::string::npos)
      << e.what();
  EXPECT_NE(std::string(e.what()).find("line 2 already opens o<1> if"), std::string::npos)
      << e.what();
}

TEST(OWordLabels, EveryKindOfBlockClaimsTheLabel) {
  // while then if, repeat then if, if then while, named labels too.
  EXPECT_EQ(
      readError("#1=0\no1 while [#1 LT 2]\n#1=[#1+1]\no1 endwhile\no1 if [1]\no1 endif\n").line(),
      5);
  EXPECT_EQ(readError("o<a> repeat [2]\no<a> endrepeat\no<a> if [1]\no<a> endif\n").line(), 3);
  EXPECT_EQ(readError("o<a> repeat [2]\no<a> endrepeat\no<a> repeat [2]\no<a> endrepeat\n").line(),
            3);
  EXPECT_EQ(readError("o1 if [1]\no1 endif\no1 while [0]\no1 endwhile\n").line(), 3);
  // A do leaves no error itself; its closing while finds the if's claim.
  EXPECT_EQ(readError("o1 if [1]\no1 endif\no1 do\nG0 X1\no1 while [0]\n").line(), 5);
}

TEST(OWordLabels, NestedBlockOfTheSameLabelIsAnErrorEvenWhileSkipping) {
  // rs274 reads the lines of the label it skips to: the inner if is a duplicate
  // although the outer if is false.
  const GcodeError e = readError(
      "o1 if [0]\n"
      "  G0 X3\n"
      "  o1 if [1]\n"
      "  o1 endif\n"
      "o1 endif\n");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), 3);
  EXPECT_EQ(readError("o1 while [0]\no1 repeat [2]\no1 endrepeat\no1 endwhile\n").line(), 2);
}

TEST(OWordLabels, LoopsComingRoundAgainAndSubroutineScopesAreNoDuplicates) {
  const auto blocks = readAll(
      "o1 sub\n"           // 1: a sub name is no control label
      "  o1 if [1]\n"      // 2: label 1 in sub 1
      "    G0 X#1\n"       // 3
      "  o1 endif\n"       // 4
      "o1 endsub\n"        // 5
      "o<t> sub\n"         // 6
      "  o1 if [1]\n"      // 7: label 1 in sub t
      "    G0 Y#1\n"       // 8
      "  o1 endif\n"       // 9
      "o<t> endsub\n"      // 10
      "o1 call [1]\n"      // 11
      "o1 call [2]\n"      // 12: the same if line again
      "o1 if [1]\n"        // 13: label 1 in the program
      "  o<t> call [3]\n"  // 14
      "o1 endif\n"         // 15
      "#2 = 0\n"           // 16
      "o2 while [#2 LT 3]\n"
      "  #2 = [#2 + 1]\n"
      "  G0 Z#2\n"
      "o2 endwhile\n");
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(values(blocks, 'Y'), (std::vector<double>{3.0}));
  EXPECT_EQ(values(blocks, 'Z'), (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST(OWordLabels, ASecondDoOfALabelLoopsBackToTheFirst) {
  // rs274: the second do finds label 2 claimed by the first and its closing while
  // jumps back there (X4 at line 4), then runs on into the second loop again.
  const auto blocks = readAll(
      "#1 = 0\n"
      "o2 do\n"
      "  #1 = [#1 + 1]\n"
      "  G0 X#1\n"
      "o2 while [#1 LT 2]\n"
      "o2 do\n"
      "  #1 = [#1 + 1]\n"
      "  G0 Y#1\n"
      "o2 while [#1 LT 4]\n");
  ASSERT_EQ(blocks.size(), 5u);
  std::vector<int> lines;
  for (const Block& b : blocks) lines.push_back(b.pos.line);
  EXPECT_EQ(lines, (std::vector<int>{4, 4, 8, 4, 8}));
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{1.0, 2.0, 4.0}));
  EXPECT_EQ(values(blocks, 'Y'), (std::vector<double>{3.0, 5.0}));
}

}  // namespace
}  // namespace mdhd::gcode

namespace mdhd::gcode {
namespace {

using testing::memoryLoader;
using testing::readAll;
using testing::readError;
using testing::values;

// A bare `O1000` line (Fanuc-style program number, as Mastercam-like posts start a
// program): LinuxCNC 2.9 runs on into it; mdhd refused it ("Unknown command in O
// line"). Oracle program 27 holds rs274's trace of a whole such program.
TEST(OWordProgramNumber, ABareOWordLineIsRunThrough) {
  const auto blocks = readAll(
      "%\n"
      "O1000 (program name)\n"
      "G0 X1\n"
      "N10 O0002\n"
      "o<named> ; comment\n"
      "G0 X2\n"
      "O1000 sub\n"
      "G0 X7\n"
      "O1000 endsub\n"
      "O1000 call\n"
      "%\n");
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{1.0, 2.0, 7.0}));
  EXPECT_EQ(blocks[1].pos.line, 6);
}

TEST(OWordProgramNumber, WordsAfterItOrInsideASubroutineAreErrors) {
  GcodeError e = readError("G0 X0\nO1000 G0 X5\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 7);
  EXPECT_STREQ(e.what(), "Unknown command in O line");
  // rs274: "Nested subroutine definition" at the program number's line.
  e = readError("o100 sub\n  O1000\no100 endsub\no100 call\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 3);
  EXPECT_NE(std::string(e.what()).find("Nested subroutine definition"), std::string::npos)
      << e.what();
  // rs274: "Fanuc 'O....' subroutine must be called with 'M98'" in the sub's file.
  e = readError("G0 X0\no<ex> call\n", {},
                memoryLoader({{"ex", "o<ex> sub\nG0 X3\nO1000\no<ex> endsub\n"}}));
  EXPECT_EQ(e.pos().file, "ex.ngc");
  EXPECT_EQ(e.line(), 3);
  EXPECT_NE(std::string(e.what()).find("only by M98"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace mdhd::gcode

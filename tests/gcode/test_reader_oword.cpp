// O-word control flow through the Reader.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/gcode/test_reader_helpers.h"

namespace mdhd::gcode {
namespace {

using testing::memoryLoader;
using testing::readAll;
using testing::readError;
using testing::values;

std::vector<double> xs(const std::string& program, ReaderOptions options = {}) {
  return values(readAll(program, options), 'X');
}

TEST(OWord, SubroutineDefinitionIsSkippedAndCallPassesArguments) {
  ParameterStore params;
  params.set(1, 99.0);
  const auto blocks = readAll(
      "o100 sub\n"
      "  G0 X[#1 + #3] Y#2\n"
      "  #<local> = 5\n"
      "  #<_glob> = #1\n"
      "o100 endsub\n"
      "G0 X-1\n"
      "o100 call [10] [20] [3]\n"
      "G0 X#1 Y[EXISTS[#<local>]] Z#<_glob>\n",
      params);
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{-1.0, 13.0, 99.0}));
  EXPECT_EQ(values(blocks, 'Y'), (std::vector<double>{20.0, 0.0}));
  EXPECT_EQ(values(blocks, 'Z'), std::vector<double>{10.0});
  EXPECT_EQ(blocks[1].pos.line, 2);  // the block inside the sub keeps its own line
  EXPECT_EQ(blocks[2].pos.line, 8);
}

TEST(OWord, SubDefinedLaterInTheFileIsFound) {
  const auto blocks = readAll(
      "o<later> call [4]\n"
      "G0 X100\n"
      "M2\n"
      "o<later> sub\n"
      "G0 X#1\n"
      "o<later> endsub\n");
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{4.0, 100.0}));
  EXPECT_EQ(blocks[0].pos.line, 5);
  EXPECT_EQ(blocks[1].pos.line, 2);
}

TEST(OWord, ReturnValues) {
  const auto blocks = readAll(
      "o<sq> sub\n"
      "  o<sq> return [#1 * #1]\n"
      "  G0 X-999\n"
      "o<sq> endsub\n"
      "o<nothing> sub\n"
      "o<nothing> endsub\n"
      "o<sq> call [3]\n"
      "G0 X#<_value> Y#<_value_returned>\n"
      "o<nothing> call\n"
      "G0 X#<_value> Y#<_value_returned>\n");
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{9.0, 0.0}));
  EXPECT_EQ(values(blocks, 'Y'), (std::vector<double>{1.0, 0.0}));
}

TEST(OWord, EndsubWithValue) {
  const auto blocks = readAll("o1 sub\no1 endsub [7]\no1 call\nX#<_value>\n");
  EXPECT_EQ(values(blocks, 'X'), std::vector<double>{7.0});
}

TEST(OWord, NestedCallsKeepLocalsPerLevel) {
  const auto blocks = readAll(
      "o<inner> sub\n"
      "  #<v> = 2\n"
      "  G0 X#1 Y#<v>\n"
      "o<inner> endsub\n"
      "o<outer> sub\n"
      "  #<v> = 1\n"
      "  o<inner> call [#1 + 1]\n"
      "  G0 X#1 Y#<v>\n"
      "o<outer> endsub\n"
      "o<outer> call [10]\n");
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{11.0, 10.0}));
  EXPECT_EQ(values(blocks, 'Y'), (std::vector<double>{2.0, 1.0}));
}

TEST(OWord, RecursionUpToTheDepthLimit) {
  // Counts down from #1: calls nest #1 + 1 levels deep.
  const std::string sub =
      "o<down> sub\n"
      "  G0 X#1\n"
      "  o1 if [#1 GT 0]\n"
      "    o<down> call [#1 - 1]\n"
      "  o1 endif\n"
      "o<down> endsub\n";
  // LinuxCNC: 10 call levels counting the program itself, so 9 nested calls.
  EXPECT_EQ(xs(sub + "o<down> call [8]\n").size(), 9u);
  const GcodeError e = readError(sub + "o<down> call [9]\n");
  EXPECT_STREQ(e.what(), "Too many nested subroutine calls (limit 10 levels)");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.column(), 5);
}

TEST(OWord, IfElseifElse) {
  const std::string program =
      "o10 if [#1 EQ 1]\n"
      "  X1\n"
      "o10 elseif [#1 EQ 2]\n"
      "  X2\n"
      "o10 elseif [#1 EQ 3]\n"
      "  X3\n"
      "o10 else\n"
      "  X4\n"
      "o10 endif\n"
      "X5\n";
  for (int i = 1; i <= 4; ++i) {
    EXPECT_EQ(xs("#1=" + std::to_string(i) + "\n" + program),
              (std::vector<double>{static_cast<double>(i), 5.0}))
        << i;
  }
}

TEST(OWord, NestedIfs) {
  const auto got =
      xs("o1 if [1]\n"
         "  o2 if [0]\n"
         "    X1\n"
         "  o2 else\n"
         "    X2\n"
         "    o3 if [1]\n"
         "      X3\n"
         "    o3 endif\n"
         "  o2 endif\n"
         "o1 else\n"
         "  o4 if [1]\n"
         "    X4\n"
         "  o4 endif\n"
         "o1 endif\n");
  EXPECT_EQ(got, (std::vector<double>{2.0, 3.0}));
}

TEST(OWord, WhileLoop) {
  const auto got =
      xs("#1 = 0\n"
         "o200 while [#1 LT 3]\n"
         "  X#1\n"
         "  #1 = [#1 + 1]\n"
         "o200 endwhile\n"
         "X99\n");
  EXPECT_EQ(got, (std::vector<double>{0.0, 1.0, 2.0, 99.0}));
}

TEST(OWord, WhileNeverEntered) {
  EXPECT_EQ(xs("o1 while [0]\nX1\no1 endwhile\nX2\n"), std::vector<double>{2.0});
}

TEST(OWord, NestedLoopsAndLineNumbers) {
  const auto blocks = readAll(
      "#1 = 0\n"
      "o1 while [#1 LT 2]\n"
      "  #2 = 0\n"
      "  o2 while [#2 LT 2]\n"
      "    X[#1 * 10 + #2]\n"
      "    #2 = [#2 + 1]\n"
      "  o2 endwhile\n"
      "  #1 = [#1 + 1]\n"
      "o1 endwhile\n"
      "X99\n");
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{0.0, 1.0, 10.0, 11.0, 99.0}));
  for (std::size_t i = 0; i + 1 < blocks.size(); ++i) EXPECT_EQ(blocks[i].pos.line, 5);
  EXPECT_EQ(blocks.back().pos.line, 10);
}

TEST(OWord, DoWhileRunsAtLeastOnce) {
  EXPECT_EQ(xs("#1 = 5\no1 do\n  X#1\n  #1 = [#1 + 1]\no1 while [#1 LT 3]\nX9\n"),
            (std::vector<double>{5.0, 9.0}));
  EXPECT_EQ(xs("#1 = 0\no1 do\n  X#1\n  #1 = [#1 + 1]\no1 while [#1 LT 3]\nX9\n"),
            (std::vector<double>{0.0, 1.0, 2.0, 9.0}));
}

TEST(OWord, Repeat) {
  EXPECT_EQ(xs("o1 repeat [3]\n  X1\no1 endrepeat\nX2\n"),
            (std::vector<double>{1.0, 1.0, 1.0, 2.0}));
  EXPECT_EQ(xs("o1 repeat [0]\n  X1\no1 endrepeat\nX2\n"), std::vector<double>{2.0});
  EXPECT_EQ(xs("o1 repeat [-4]\n  X1\no1 endrepeat\nX2\n"), std::vector<double>{2.0});
}

TEST(OWord, BreakAndContinue) {
  const auto got =
      xs("#1 = 0\n"
         "o1 while [#1 LT 10]\n"
         "  #1 = [#1 + 1]\n"
         "  o2 if [#1 EQ 2]\n"
         "    o1 continue\n"
         "  o2 endif\n"
         "  o3 if [#1 EQ 4]\n"
         "    o1 break\n"
         "  o3 endif\n"
         "  X#1\n"
         "o1 endwhile\n"
         "X99\n");
  EXPECT_EQ(got, (std::vector<double>{1.0, 3.0, 99.0}));
}

TEST(OWord, BreakAndContinueInRepeatAndDo) {
  // LinuxCNC: break / continue work for while and do loops only.
  EXPECT_STREQ(readError("o1 repeat [5]\no1 break\no1 endrepeat\n").what(),
               "o<1> break: no matching while/do label");
  EXPECT_EQ(xs("#1=0\no1 do\n#1=[#1+1]\no2 if [#1 EQ 2]\no1 continue\no2 endif\n"
               "o3 if [#1 EQ 4]\no1 break\no3 endif\nX#1\no1 while [#1 LT 10]\nX99\n"),
            (std::vector<double>{1.0, 3.0, 99.0}));
}

TEST(OWord, ExternalSubroutineIsLoadedOnce) {
  int loads = 0;
  auto files = memoryLoader({{"sq", "(square)\no<sq> sub\n  G1 X#1\n o<sq> endsub\nM2\nX-1\n"}});
  SubroutineLoader counting = [&](std::string_view name) {
    ++loads;
    return files(name);
  };
  ParameterStore params;
  const auto blocks = readAll("o<sq> call [1]\no<sq> call [2]\nG0 X3\n", params, counting);
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(loads, 1);
  EXPECT_EQ(blocks[0].pos.file, "sq.ngc");
  EXPECT_EQ(blocks[0].pos.line, 3);
  EXPECT_EQ(blocks[2].pos.file, "");
}

TEST(OWord, ErrorsInExternalFilesNameTheFile) {
  const GcodeError e = readError(
      "G0\no<bad> call\n", {}, memoryLoader({{"bad", "o<bad> sub\n G0 X[1/0]\no<bad> endsub\n"}}));
  EXPECT_STREQ(e.what(), "Attempt to divide by zero");
  EXPECT_EQ(e.pos().file, "bad.ngc");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 8);
}

TEST(OWord, Errors) {
  struct Case {
    const char* program;
    const char* message;
    int line;
    int column;
  } cases[] = {
      {"G0\no<nope> call\n",
       "Unknown subroutine o<nope>: not defined in the program and no nope.ngc found", 2, 1},
      {"o1 sub\nG0\n", "o<1> sub has no matching endsub", 1, 1},
      {"  o1 if [0]\nG0\n", "o<1> if has no matching elseif / else / endif", 1, 3},
      {"N10 o1 if [1]\nG0\no1 else\nX1\n", "o<1> if has no matching endif", 1, 5},
      {"o1 while [0]\nG0\n", "o<1> while has no matching endwhile", 1, 1},
      {"G0\no1 endif\n", "o<1> endif without matching if", 2, 1},
      {"o1 if [1]\no2 endif\n", "o<2> endif without matching if", 2, 1},
      {"o1 endwhile\n", "o<1> endwhile without matching while", 1, 1},
      {"o1 endrepeat\n", "o<1> endrepeat without matching repeat", 1, 1},
      {" o1 break\n", "o<1> break: no matching while/do label", 1, 2},
      {"o1 return\n", "o<1> return outside a subroutine", 1, 1},
      {"o1 endsub\n", "o<1> endsub outside a subroutine", 1, 1},
      {"o1 sub\no2 endsub\no1 endsub\no1 call\n", "o<2> endsub inside subroutine o<1>", 2, 1},
      {"o1 sub\nG0\n o1 call\n", "o<1> sub has no matching endsub", 1, 1},
      {"o1 foo [1]\n", "Unknown command in O line", 1, 4},
      {"o1 x5\n", "Unknown command in O line", 1, 4},  // a bare o1 is a program number
      {"o call\n", "Unknown word where unary operation could be", 1, 3},
      {"o1.5 call\n", "Non-integer value for integer", 1, 2},
      {"o<abc call\n", "Named parameter not terminated", 1, 2},
      {"o1 if 1\n", "Left bracket missing after 'if'", 1, 7},
      {"o1 while\n", "Left bracket missing after 'while'", 1, 9},
      {"o1 if [1] G0\no1 endif\n", "Unexpected character after O-word", 1, 11},
      {"o1 sub\n o2 sub\n o2 endsub\no1 endsub\n",
       "Nested subroutine definition: o<2> sub inside o<1> sub", 2, 2},
      {"o1 sub\no1 endsub\no1 sub\no1 endsub\n",
       "Redefining subroutine o<1>, already defined in the program line 1", 3, 1},
      {"o1 sub\no1 endsub\n  o1 call [1] [2] [3] [4] [5] [6] [7] [8] [9] [10] [11] [12] [13] [14] "
       "[15] [16] [17] [18] [19] [20] [21] [22] [23] [24] [25] [26] [27] [28] [29] [30] [31]\n",
       "Too many subroutine arguments (more than 30)", 3, 152},
  };
  for (const Case& c : cases) {
    const GcodeError e = readError(c.program);
    EXPECT_EQ(std::string(e.what()), c.message) << c.program;
    EXPECT_EQ(e.line(), c.line) << c.program;
    EXPECT_EQ(e.column(), c.column) << c.program;
  }
}

TEST(OWord, EndlessLoopsAreStopped) {
  ReaderOptions options;
  options.max_loop_iterations = 1000;
  const GcodeError e = readError("G0\n  o7 while [1]\no7 endwhile\n", options);
  EXPECT_STREQ(e.what(), "Loop o<7> ran more than 1000 times (endless loop?)");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 3);  // the O-word that opened the loop
  const GcodeError d = readError("o7 do\no7 while [1]\n", options);
  EXPECT_STREQ(d.what(), "Loop o<7> ran more than 1000 times (endless loop?)");
  const GcodeError r = readError("o7 repeat [10**300]\no7 endrepeat\n", options);
  EXPECT_STREQ(r.what(), "Loop o<7> ran more than 1000 times (endless loop?)");
  // The step budget catches loops that each stay under their own cap.
  ReaderOptions steps;
  steps.max_steps = 500;
  const GcodeError s =
      readError("o1 repeat [100]\no2 repeat [100]\no2 endrepeat\no1 endrepeat\n", steps);
  EXPECT_STREQ(s.what(), "Program exceeds the limit of 500 lines read (endless loop?)");
}

TEST(OWord, BlocksNeverClosedAreCapped) {
  // Ifs opened line after line and never closed: memory must not grow unbounded.
  std::string program;
  for (int i = 0; i < 10'001; ++i) program += "o" + std::to_string(i) + " if [1]\n";
  const GcodeError e = readError(program);
  EXPECT_STREQ(e.what(),
               "Too many nested O-word blocks (more than 10000 open if / while / do / repeat)");
  EXPECT_EQ(e.line(), 10'001);
}

TEST(OWord, InfiniteRecursionIsStopped) {
  const GcodeError e = readError("o1 sub\no1 call\no1 endsub\no1 call\n");
  EXPECT_STREQ(e.what(), "Too many nested subroutine calls (limit 10 levels)");
}

TEST(OWord, LabelsAreIntegerValuesOrNames) {
  // o0100, o100 and o[50*2] are the same label; names ignore case and blanks.
  EXPECT_EQ(xs("#1 = 100\no[50*2] if [1]\nX1\no#1 else\nX2\no0100 endif\nX3\n"),
            (std::vector<double>{1.0, 3.0}));
  EXPECT_EQ(xs("o< My Sub > sub\nX#1\no<mysub> endsub\nO<MYSUB> CALL [5]\n"),
            std::vector<double>{5.0});
}

TEST(OWord, KeywordsIgnoreCaseAndBlanks) {
  EXPECT_EQ(xs("#1=0\nO100 WHILE [#1 LT 2]\nX#1\n#1=[#1+1]\nO 1 0 0 End While\nX9\n"),
            (std::vector<double>{0.0, 1.0, 9.0}));
}

TEST(OWord, CommentsBetweenCallArguments) {
  EXPECT_EQ(xs("o1 sub\nX[#1 + #2]\no1 endsub\no1 call [1] (x) [2] (y)\n"),
            std::vector<double>{3.0});
}

TEST(OWord, ExternalFileIsPreferredToALaterDefinition) {
  // LinuxCNC looks for <name>.ngc before searching on in the current file.
  // (Like the interpreter, stop at M2: the definition after it would be a redefinition.)
  ParameterStore params;
  Reader reader(makeStringSource("o<s> call\nM2\no<s> sub\nX1\no<s> endsub\n"), params,
                memoryLoader({{"s", "o<s> sub\nX2\no<s> endsub\n"}}));
  Block block;
  ASSERT_TRUE(reader.next(block));
  EXPECT_EQ(block.pos.file, "s.ngc");
  EXPECT_EQ(testing::wordValue(block, 'X'), 2.0);
  ASSERT_TRUE(reader.next(block));
  EXPECT_EQ(testing::wordValue(block, 'M'), 2.0);
  EXPECT_STREQ(readError("o<s> call\nM2\no<s> sub\nX1\no<s> endsub\n", {},
                         memoryLoader({{"s", "o<s> sub\nX2\no<s> endsub\n"}}))
                   .what(),
               "Redefining subroutine o<s>, already defined in s.ngc line 1");
}

TEST(OWord, ExternalSubCallsASubOfTheProgram) {
  ParameterStore params;
  const auto blocks = readAll("o<inner> sub\nX#1\no<inner> endsub\no<outer> call [7]\nX9\n", params,
                              memoryLoader({{"outer",
                                             "o<outer> sub\no<inner> call [#1 * 2]\n"
                                             "Y1\no<outer> endsub\n"}}));
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(values(blocks, 'X'), (std::vector<double>{14.0, 9.0}));
  EXPECT_EQ(blocks[0].pos.file, "");
  EXPECT_EQ(blocks[1].pos.file, "outer.ngc");
  EXPECT_EQ(blocks[1].pos.line, 3);
}

TEST(OWord, ExternalFileWithoutTheSubIsAnError) {
  const GcodeError e =
      readError("G0\no<x> call\n", {}, memoryLoader({{"x", "(nothing here)\nG0\n"}}));
  EXPECT_STREQ(e.what(), "File x.ngc does not define o<x> sub");
  EXPECT_EQ(e.pos().file, "");
  EXPECT_EQ(e.line(), 2);
}

TEST(OWord, DirectoryLoaderReadsFiles) {
  const auto dir = std::filesystem::temp_directory_path() / "mdhd_reader_loader_test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "plus.ngc");
    out << "o<plus> sub\no<plus> return [#1 + #2]\no<plus> endsub\n";
  }
  ParameterStore params;
  Reader reader(makeStringSource("o<plus> call [2] [3]\nX#<_value>\n"), params,
                makeDirectoryLoader({"/nonexistent", dir.string()}));
  Block block;
  ASSERT_TRUE(reader.next(block));
  EXPECT_EQ(block.words.at(0).value, 5.0);
  EXPECT_FALSE(reader.next(block));
  std::filesystem::remove_all(dir);
}

TEST(OWord, SkippedLinesAreNotEvaluated) {
  // Errors in branches not taken do not count (only the O-word lines are read).
  EXPECT_EQ(xs("o1 if [0]\nX[1/0] #<undefined>\no1 endif\nX1\n"), std::vector<double>{1.0});
}

TEST(OWord, ManyElseifsDoNotRecurse) {
  std::string program = "#1 = 4999\no1 if [#1 EQ -1]\nX-1\n";
  for (int i = 0; i < 5000; ++i) {
    program += "o1 elseif [#1 EQ " + std::to_string(i) + "]\nX" + std::to_string(i) + "\n";
  }
  program += "o1 endif\n";
  EXPECT_EQ(xs(program), std::vector<double>{4999.0});
}

}  // namespace
}  // namespace mdhd::gcode

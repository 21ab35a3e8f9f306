// Offsets a program writes through parameters (#5161.. #5389) taking effect
// when LinuxCNC reads them, tool table edits (G10 L1/L10/L11) and G43.2.
#include <gtest/gtest.h>

#include "oracle_support.h"

namespace mdhd::gcode::testing {
namespace {

InterpreterConfig tools() {
  InterpreterConfig c;
  c.tools.add({1, 50.0, 6.0});
  c.tools.add({2, 75.0, 10.0});
  return c;
}

using Result = ProgramRun;

Result runWithTools(const std::string& program, InterpreterConfig config = tools()) {
  return runProgram(program, std::move(config));
}

TEST(OffsetParameters, SelectingASystemReadsItsParameters) {
  const Result r = runWithTools("#5241=10\n#5242=-3\nG55 G0 X0 Y0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 1u);
  EXPECT_DOUBLE_EQ(r.motions[0].end[kX], 10.0);
  EXPECT_DOUBLE_EQ(r.motions[0].end[kY], -3.0);
}

TEST(OffsetParameters, RotationsToo) {
  // #5250: G55's XY rotation; #5390 (G59.3's, the last offset parameter).
  Result r = runWithTools("#5250=90\nG55 G0 X1 Y0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_NEAR(r.motions[0].end[kX], 0.0, 1e-12);
  EXPECT_NEAR(r.motions[0].end[kY], 1.0, 1e-12);
  r = runWithTools("G10 L2 P9 R30\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.param(5390), 30.0);
}

TEST(OffsetParameters, TheActiveSystemChangesOnlyWhenReselected) {
  const Result r = runWithTools("#5221=5\nG0 X0\nG54\nG0 X0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 2u);
  EXPECT_DOUBLE_EQ(r.motions[0].end[kX], 0.0);
  EXPECT_DOUBLE_EQ(r.motions[1].end[kX], 5.0);
}

TEST(OffsetParameters, G10KeepsTheAxesItDoesNotNameFromTheParameters) {
  const Result r = runWithTools("#5242=7\nG10 L2 P2 X1\nG55 G0 X0 Y0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.motions[0].end[kX], 1.0);
  EXPECT_DOUBLE_EQ(r.motions[0].end[kY], 7.0);
  EXPECT_DOUBLE_EQ(r.param(5241), 1.0);
  EXPECT_DOUBLE_EQ(r.param(5242), 7.0);
}

TEST(OffsetParameters, WrittenValuesAreNotOverwrittenByOtherOffsetChanges) {
  const Result r = runWithTools("#5241=10\nG10 L2 P3 X1\nG92 X0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.param(5241), 10.0);
  EXPECT_DOUBLE_EQ(r.param(5261), 1.0);
}

TEST(OffsetParameters, ProgramEndReadsG54) {
  const Result r = runWithTools("#5221=3\nG55\nM2\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_EQ(r.state.coord_system, 0);
  EXPECT_DOUBLE_EQ(r.state.g5x[0][kX], 3.0);
  EXPECT_DOUBLE_EQ(r.param(5220), 1.0);
}

TEST(OffsetParameters, G92Point3AndG28ReadTheirParameters) {
  Result r = runWithTools("#5211=4\nG92.3\nG0 X0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.motions.back().end[kX], 4.0);
  r = runWithTools("#5161=12\n#5163=-1\nG28\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.motions.back().end[kX], 12.0);
  EXPECT_DOUBLE_EQ(r.motions.back().end[kZ], -1.0);
  r = runWithTools("#5181=2\nG30 X5\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 2u);
  EXPECT_DOUBLE_EQ(r.motions[0].end[kX], 5.0);
  EXPECT_DOUBLE_EQ(r.motions[1].end[kX], 2.0);
}

TEST(ToolTableEdits, G10L1SetsLengthAndRadius) {
  const Result r = runWithTools("G10 L1 P1 Z30 R4\nT1 M6\nG43 H1\nG0 Z0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.motions.back().end[kZ], 30.0);
  EXPECT_DOUBLE_EQ(r.param(5410), 8.0);  // diameter of the tool in the spindle
}

TEST(ToolTableEdits, G10L10MakesTheCurrentZReadTheWord) {
  // At Z10 without an offset, "G10 L10 P1 Z0" gives tool 1 the length 10: with
  // G43 H1 the current point reads Z0 and the machine has not moved.
  const Result r = runWithTools("G0 Z10\nG10 L10 P1 Z0\nG43 H1\nG0 X1\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.motions.back().end[kZ], 10.0);
  EXPECT_DOUBLE_EQ(r.state.current[kZ], 0.0);
}

TEST(ToolTableEdits, G10L11MeasuresInG59Point3) {
  InterpreterConfig c = tools();
  c.work_offsets[8] = {0.0, 0.0, 2.0};
  c.work_offsets[0] = {0.0, 0.0, 5.0};
  // Machine Z 10: in G59.3 that is 8, so the length is 8 - 0.
  const Result r = runWithTools("G53 G0 Z10\nG10 L11 P2 Z0\nG43 H2\n", c);
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.state.tool_length, 8.0);
}

TEST(ToolTableEdits, Errors) {
  EXPECT_STREQ(runWithTools("G10 L1 P7 Z1\n").error->what(),
               "Requested tool 7 not found in the tool table");
  EXPECT_STREQ(runWithTools("G10 L1 P1\n").error->what(), "G10 L1 without offsets has no effect");
  EXPECT_STREQ(runWithTools("G10 L1 P1 X1\n").error->what(),
               "G10 L1: only Z (length) and R (radius) offsets are kept");
  EXPECT_STREQ(runWithTools("G10 L20 P1 X1 R5\n").error->what(), "R not allowed in G10 L20");
  EXPECT_STREQ(runWithTools("G10 L2 P1 X1 I5\n").error->what(),
               "I J words not allowed with G10 L2");
}

TEST(AdditionalToolOffset, G43Point2AddsToTheOffsetInEffect) {
  Result r = runWithTools("G43 H1\nG43.2 H2\nG0 Z0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.motions.back().end[kZ], 125.0);
  r = runWithTools("G43 H1\nG43.2 Z1.5\nG0 Z0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 1u);  // the Z word is the offset, not a move
  EXPECT_DOUBLE_EQ(r.motions.back().end[kZ], 51.5);
  EXPECT_STREQ(runWithTools("G43.2\n").error->what(),
               "G43.2: No axes specified and H word missing");
  EXPECT_STREQ(runWithTools("G43.2 X1\n").error->what(),
               "G43.2 offsets other than Z are not supported");
}

}  // namespace
}  // namespace mdhd::gcode::testing

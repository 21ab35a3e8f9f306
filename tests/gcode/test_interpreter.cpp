// Interpreter features one by one, with exact expected machine values.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "oracle_support.h"

namespace mdhd::gcode::testing {
namespace {

InterpreterConfig baseConfig() {
  InterpreterConfig c;
  c.tools.add({1, 50.0, 6.0});
  c.tools.add({2, 75.0, 10.0});
  return c;
}

using Result = ProgramRun;

Result run(const std::string& program, InterpreterConfig config = baseConfig()) {
  return runProgram(program, std::move(config));
}

void expectEnd(const RecordedMotion& m, double x, double y, double z) {
  EXPECT_NEAR(m.end[kX], x, 1e-9);
  EXPECT_NEAR(m.end[kY], y, 1e-9);
  EXPECT_NEAR(m.end[kZ], z, 1e-9);
}

TEST(InterpreterErrors, TwoCodesOfOneModalGroupNameTheColumn) {
  const Result r = run("G0 X1\nG0 G1 X2\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Two G codes used from same modal group");
  EXPECT_EQ(r.error->line(), 2);
  EXPECT_EQ(r.error->column(), 4);
  EXPECT_EQ(r.motions.size(), 1u);
}

// Words read as integers beyond an int's range are errors at the word, not undefined
// casts (found by fuzz_gcode_interpreter under UBSan).
TEST(InterpreterErrors, IntegerWordsBeyondAnIntAreErrors) {
  for (const char* program :
       {"T555555555555 M6\n", "G43 H12222222222\n", "M61 Q100000000000000000000\n",
        "G10 L1000000000000000000000000000000 P1\n", "G10 L1 P1000000000000 Z5\n",
        "G0 X0 Y0 Z5\nG81 X1 Y1 Z-1 R1 L1000000000000000 F100\n",
        "G41 D1000000000000000 G1 X5 F100\n"}) {
    const Result r = run(program);
    ASSERT_TRUE(r.error) << program;
    EXPECT_NE(std::string(r.error->what()).find("word value out of range"), std::string::npos)
        << program << ": " << r.error->what();
  }
}

TEST(InterpreterErrors, UnknownCodesAndMissingAxes) {
  Result r = run("G21\nG68 X0\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Unknown g code used");
  EXPECT_EQ(r.error->column(), 1);
  r = run("M123\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Unknown m code used");
  // Codes LinuxCNC runs and mdhd does not: named, at their column (they were
  // "Unknown g code used", which sends a machinist looking for a typing error).
  const std::pair<const char*, const char*> unsupported[] = {
      {"G0 X1 G7\n", "G7 (lathe diameter/radius mode) is not supported"},
      {"G0 X1 G18.1\n", "G18.1 (UVW plane selection) is not supported"},
      {"G0 X1 G71.2\n", "G71.2 (lathe roughing/finishing cycle) is not supported"},
      {"G0 X1 G76\n", "G76 (threading cycle) is not supported"},
      {"G0 X1 M73\n", "M73 (modal state save/restore) is not supported"},
      {"G0 X1 M98\n",
       "M98 (Fanuc-style subprogram call/return; use O-word sub/call) is not supported"}};
  for (const auto& [program, message] : unsupported) {
    r = run(program);
    ASSERT_TRUE(r.error) << program;
    EXPECT_STREQ(r.error->what(), message);
    EXPECT_EQ(r.error->column(), 7) << program;
  }
  r = run("G7.5\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Unknown g code used");
  r = run("G0 X1 W5\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(),
               "Bad character 'w' used: the machine has no W axis (its axes: X Y Z A B C)");
  EXPECT_EQ(r.error->column(), 7);
  InterpreterConfig xyz = baseConfig();
  xyz.axis_mask = 0x7;  // a 3-axis machine: A is not there
  r = run("G0 X1 A5\n", xyz);
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(),
               "Bad character 'a' used: the machine has no A axis (its axes: X Y Z)");
  r = run("X1\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Cannot use axis values without a g code that uses them");
  r = run("G80 X1\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Cannot use axis values with G80");
}

// Error texts as rs274 prints them (LinuxCNC 2.9), checked against it by hand:
// the oracle traces stop at a program's first error.
void expectError(const std::string& program, const char* message, int line = 2) {
  const Result r = run(program);
  ASSERT_TRUE(r.error) << program;
  EXPECT_STREQ(r.error->what(), message) << program;
  EXPECT_EQ(r.error->line(), line) << program;
}

TEST(InterpreterErrors, DigitalIoWords) {
  expectError("G21\nM62\n", "No valid P word with M62");
  expectError("G21\nM65\n", "No valid P word with M65");
  expectError("G21\nM62 P0 M63 P1\n", "Two M codes used from same modal group");
  expectError("G21\nM62 P0 Q1\n",
              "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that "
              "uses it");
  expectError("G21\nM66\n", "Need to have either a valid P or a valid E word with M66");
  expectError("G21\nM66 P-1\n", "Need to have either a valid P or a valid E word with M66");
  expectError("G21\nM66 P0 E0\n", "Invalid to select both a digital and an analog input with M66");
  expectError("G21\nM66 P0 L1\n", "Zero timeout with wait type != immediate return");
  expectError("G21\nM66 P0 L2 Q0.4\n", "Zero timeout with wait type != immediate return");
  expectError("G21\nM66 E0 L1 Q1\n",
              "Can't select analog input with wait type != immediate return");
  expectError("G21\nM66 P0 L-1\n", "Negative l word used");
  expectError("G21\nM66 P0 L0.5\n", "Non integer value for integer");
  // Accepted, and nothing moves.
  for (const char* ok : {"M62 P-1\n", "M64 P1.5\n", "M66 P0 L1 Q1\n", "M66 P0 L5 Q1\n",
                         "M66 P0 Q-1\n", "M66 E0 L0\n", "G1 X1 F100 M66 P0\n"}) {
    const Result r = run(ok);
    EXPECT_FALSE(r.error) << ok << (r.error ? r.error->what() : "");
  }
}

// M19 (orient spindle), M67/M68 (analog outputs) and the $ spindle word, as rs274
// takes them (each line below checked against it; oracle programs 25 and
// 99_reject_g33_after_m19). mdhd refused M19, M67 and M68 as unknown codes.
TEST(InterpreterErrors, OrientSpindleAnalogOutputsAndSpindleWord) {
  expectError("G21\nM67 Q5\n", "Invalid analog index with M67 (an E word from 0 names the output)");
  expectError("G21\nM68 E-0.6 Q5\n",
              "Invalid analog index with M68 (an E word from 0 names the output)");
  expectError("G21\nM67 E0 Q5 P1\n",
              "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 "
              "M63 M64 M65 M66 or user M code to use it");
  expectError("G21\nM62 P1 M67 E0 Q1\n", "Two M codes used from same modal group");
  expectError("G21\nM19 P0.5\n", "P value not an integer with M19 G2 or G3");
  expectError("G21\nM19 P3\n", "P value must be 0,1,or 2 with M19");
  expectError("G21\nM19 R-10\n", "R value must be within 0..360 with M19");
  expectError("G21\nM19 R400\n", "R value must be within 0..360 with M19");
  expectError("G21\nM19 Q0\n", "Q word with M19 requires a value > 0");
  expectError("G21\nM3 S100 M19\n", "Two M codes used from same modal group");
  expectError("G21\nM19 E1\n", "E word with no G76, M66, M67 or M68 to use it");
  // Orienting stops the spindle: G33 then needs M3 again.
  expectError("G21\nS100 M3\nM19 R10\nG33 Z-1 K1\n", "Spindle not turning in G33", 4);
  expectError("G21\nM3 S100 $1\n", "Invalid spindle ($) number: the machine has one spindle, $0");
  expectError("G21\nM3 S100 $-2\n", "Invalid spindle ($) number: the machine has one spindle, $0");
  expectError("G21\nM3 S100 $-1 $0\n", "Multiple spindle choice ($) words on one line");
  expectError("G21\nG0 X2 $0\n",
              "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G96, G97 or S "
              "word to use it");
  expectError("G21\nG95 $0\n",
              "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G96, G97 or S "
              "word to use it");
  const Result r = run("S100 M3\nM19 R90 Q2 P1\n");
  ASSERT_FALSE(r.error) << r.error->what();
  std::vector<SpindleState> spindle;
  for (const Event& e : r.events)
    if (e.type == EventType::kSpindle) spindle.push_back(e.spindle);
  EXPECT_EQ(spindle, (std::vector<SpindleState>{SpindleState::kClockwise, SpindleState::kOff}));
  EXPECT_EQ(r.state.spindle, SpindleState::kOff);
  // Accepted ($ drops its fraction, $-1 is every spindle), and nothing moves.
  for (const char* ok :
       {"M67 E0 Q5\n", "M67 E0\n", "M68 E2 Q-3\n", "M67 E-0.4 Q5\n", "M67 E0 Q1 G1 X3 F100\n",
        "M19\n", "M19 P0.0005\n", "M19 R360\n", "M19 G4 P1\n", "M3 S100 $-1\n", "M3 $0.99 S100\n",
        "M3 $-1.99 S100\n", "S100 $0\n", "M5 $-1\n", "G97 S100 $0\n"}) {
    const Result ok_run = run(ok);
    EXPECT_FALSE(ok_run.error) << ok << (ok_run.error ? ok_run.error->what() : "");
  }
}

// G52 (LinuxCNC's local offset; mdhd refused it as an unknown code): the named axes'
// G92 offsets become the words, kept in #5211.. like G92's (oracle program 26).
TEST(Interpreter, G52SetsTheG92OffsetsOfTheNamedAxes) {
  const Result r = run("G0 X5 Y5 Z5\nG52 X10 Y20\nG0 X0\nG52 Z3\nG91 G52 X1\nG90 G0 X0 Y0 Z0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 3u);
  expectEnd(r.motions[1], 10.0, 5.0, 5.0);  // Y and Z left out: the machine stays there
  expectEnd(r.motions[2], 1.0, 20.0, 3.0);  // G91 does not make G52 incremental
  EXPECT_EQ(r.param(5210), 1.0);
  EXPECT_EQ(r.param(5211), 1.0);
  EXPECT_EQ(r.param(5212), 20.0);
  EXPECT_EQ(r.param(5213), 3.0);
  expectError("G21\nG52\n", "All axes missing with G52");
  expectError("G21\nG52 X1 G0 Y3\n", "Cannot use two G codes that both use axis values");
  expectError("G21\nG52 G92 X1\n", "Two G codes used from same modal group");
}

// G43.2 with neither or both of H and axis words: rs274's two messages (mdhd said
// "needs either an H word or axis offsets, not both" for both, wrong for the first).
TEST(InterpreterErrors, G43Point2WordsNameWhatIsWrong) {
  expectError("G21\nG43.2\n", "G43.2: No axes specified and H word missing");
  expectError("G21\nT1 M6\nG43.2 H1 Z5\n", "G43.2: Can not have both H and axis words", 3);
}

TEST(InterpreterErrors, LeftHandTappingNeedsTheSpindleCounterclockwise) {
  expectError("G21 G0 Z2 F100\nG74 X1 R1 Z-1\n", "Spindle not turning in G74");
  expectError("G21 G0 Z2 F100 S100 M3\nG74 X1 R1 Z-1\n", "Spindle turning clockwise in G74");
  const Result r = run("G21 G0 Z2 F100 S100 M4\nG74 X1 R1 Z-1 P0.5\nG80\n");
  ASSERT_FALSE(r.error) << r.error->what();
  // Z2; over, down to R, feed in, feed out to R (LinuxCNC starts in G99, as rs274 shows)
  ASSERT_EQ(r.motions.size(), 5u);
  expectEnd(r.motions[3], 1, 0, -1);
  expectEnd(r.motions[4], 1, 0, 1);
}

TEST(InterpreterErrors, G80BesideAnotherMotionCodeIsIgnored) {
  expectError("G21\nG0 G80 G1 X1\n", "Two G codes used from same modal group");
  expectError("G21\nG80 G80 X1\n", "Cannot use axis values with G80");
  const Result r = run("G21 F100\nG1 G80 X1\nG80 G0 X2\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 2u);
  EXPECT_EQ(r.motions[0].type, MotionType::kFeed);
  EXPECT_EQ(r.motions[1].type, MotionType::kRapid);
}

TEST(InterpreterErrors, ReferencePointWithCutterComp) {
  expectError("G21 F100\nG41 D1 G1 X10\nG30.1\n",
              "Cannot set reference point with cutter compensation in effect", 3);
}

TEST(InterpreterErrors, PolarCoordinates) {
  expectError("G21\nG0 X1 @5 ^0\n", "Cannot specify both polar coordinate and X word");
  expectError("G21\nG0 Y1 @5 ^0\n", "Cannot specify both polar coordinate and Y word");
  expectError("G21\nG53 G0 @5 ^0\n", "Cannot use polar coordinates with G53");
  expectError("G21\nG28 @5\n", "Polar coordinates can only be used for motion");
  expectError("G21\nG92 @1\n", "Polar coordinates can only be used for motion");
  expectError("G21\nG0 @5\n", "Must specify angle in polar coordinate if at the origin");
  expectError("G21\nG91 G0 @1\n",
              "Incremental motion with polar coordinates is indeterminate when at the origin");
  expectError("G21\nG91 G0 ^10\n",
              "G91 motion with polar coordinates is indeterminate when at the origin");
  expectError("G21\n@5 ^0\n", "Cannot use axis values without a g code that uses them");
  // A repeated @ or ^ is no error in rs274: the last one counts.
  const Result r = run("G21\nG0 @5 ^30 @6\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 1u);
  expectEnd(r.motions[0], 6 * std::cos(M_PI / 6), 3, 0);
}

TEST(InterpreterErrors, RejectedBlockChangesNothing) {
  // G20 and G91 come before the failing arc in execution order; none may stick.
  RecordingSink sink;
  Interpreter interp(baseConfig(), sink);
  EXPECT_THROW(interp.run(makeStringSource("G0 X1\nG20 G91 G2 X5 Y0 I1 J0 F100\n")), GcodeError);
  EXPECT_FALSE(interp.state().inch);
  EXPECT_FALSE(interp.state().incremental);
  EXPECT_EQ(interp.state().motion, 0);
  EXPECT_DOUBLE_EQ(interp.state().current[kX], 1.0);
}

TEST(InterpreterErrors, FeedRules) {
  Result r = run("G1 X1\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Cannot do G1 with zero feed rate");
  r = run("G93 G1 X10 F2\nG1 X20\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "F word missing with inverse time g1 move");
  EXPECT_EQ(r.error->line(), 2);
  r = run("T42 M6\n");
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Requested tool 42 not found in the tool table");
  EXPECT_EQ(r.error->column(), 1);
}

TEST(Interpreter, UnitsAreMillimetresOnOutput) {
  const Result r = run("G20 G0 X1 Y2 Z0.5\nG1 X2 F10\nG21 G0 X0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 3u);
  expectEnd(r.motions[0], 25.4, 50.8, 12.7);
  expectEnd(r.motions[1], 50.8, 50.8, 12.7);
  EXPECT_NEAR(r.motions[1].feed, 254.0, 1e-9);
  expectEnd(r.motions[2], 0.0, 50.8, 12.7);
}

TEST(Interpreter, WorkOffsetsFromConfigAndG10) {
  InterpreterConfig c = baseConfig();
  c.work_offsets[0] = {100, 50, -20};
  c.work_offsets[1] = {10, 10, 10};
  const Result r =
      run("G54 G0 X1 Y2 Z3\nG55 G0 X0 Y0 Z0\nG10 L2 P2 X-5\nG0 X1\nG10 L20 P2 X0\nG0 Y1\n", c);
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 4u);
  expectEnd(r.motions[0], 101, 52, -17);
  expectEnd(r.motions[1], 10, 10, 10);
  expectEnd(r.motions[2], -4, 10, 10);  // G10 L2 P2 X-5: G55 X zero now at machine -5
  expectEnd(r.motions[3], -4, 11, 10);  // L20 made the current X read 0: no X motion
  EXPECT_DOUBLE_EQ(r.state.g5x[1][kX], -4.0);
}

TEST(Interpreter, RotatedCoordinateSystem) {
  const Result r = run("G10 L2 P1 X10 R90\nG0 X10 Y0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 1u);
  expectEnd(r.motions[0], 10, 10, 0);
}

TEST(Interpreter, G92AndG53) {
  const Result r = run("G0 X10 Y10\nG92 X0 Y0\nG0 X1\nG53 G0 X0\nG92.1\nG0 X3\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 4u);
  expectEnd(r.motions[1], 11, 10, 0);
  expectEnd(r.motions[2], 0, 10, 0);
  expectEnd(r.motions[3], 3, 10, 0);
}

TEST(Interpreter, G28GoesViaIntermediatePointToStoredPosition) {
  const Result r = run("G0 X5 Y6 Z7\nG28.1\nG0 X0 Y0 Z0\nG91 G28 Z2\nG90 G28\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 6u);
  expectEnd(r.motions[2], 0, 0, 2);  // intermediate, incremental
  expectEnd(r.motions[3], 0, 0, 7);  // only Z goes to the stored position
  expectEnd(r.motions[4], 0, 0, 7);  // no axis words: intermediate = here
  expectEnd(r.motions[5], 5, 6, 7);  // then all axes
}

TEST(Interpreter, ToolLengthOffsetKeepsTheMachineStill) {
  const Result r = run("T1 M6\nG43 H1\nG0 X0 Y0 Z10\nG49\nG0 X1\nG43.1 Z-2.5\nG0 Z0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 3u);
  expectEnd(r.motions[0], 0, 0, 60);
  expectEnd(r.motions[1], 1, 0, 60);  // G49 does not move Z
  expectEnd(r.motions[2], 1, 0, -2.5);
  EXPECT_EQ(r.motions[0].comp, false);
  EXPECT_EQ(r.events.size(), 2u);  // tool change, program end
  EXPECT_EQ(r.events[0].type, EventType::kToolChange);
  EXPECT_EQ(r.events[0].tool, 1);
}

TEST(Interpreter, TcpModeOutputsTipInWorkFrame) {
  InterpreterConfig c = baseConfig();
  c.work_offsets[0] = {100, 0, -50};
  RecordingSink sink;
  Interpreter interp(c, sink);
  interp.run(makeStringSource("T1 M6\nG43.4 H1\nG0 X1 Y2 Z3 A30\nG49\nG0 Z5\n"));
  ASSERT_EQ(sink.motions.size(), 2u);
  const RecordedMotion& m = sink.motions[0];
  expectEnd(m, 101, 2, -47);  // no tool length on Z under G43.4
  EXPECT_DOUBLE_EQ(m.end[kA], 30.0);
  expectEnd(sink.motions[1], 101, 2, -45);
  const Result arc = run("T1 M6\nG43.4 H1\nG2 X0 Y0 I1 J0 F100\n");
  ASSERT_TRUE(arc.error);
  EXPECT_STREQ(arc.error->what(), "Arcs are not supported under G43.4");
}

// Switching G43.4 on or off does not move the machine: its X Y Z are re-expressed by
// the machine's kinematics (here a stand-in whose tip lies 7 mm along +Y of the joints
// per 50 mm of tool), so an axis the next block leaves out stays where the machine is.
TEST(Interpreter, TcpSwitchReexpressesThePositionAndTheMachineStays) {
  InterpreterConfig c = baseConfig();
  std::vector<std::pair<double, bool>> calls;
  c.tcp_switch = [&calls](const AxisValues& m, double length, bool to_tcp) {
    calls.emplace_back(length, to_tcp);
    AxisValues out = m;
    out[kY] += (to_tcp ? 7.0 : -7.0) * length / 50.0;
    return out;
  };
  const Result r = run("T1 M6\nG0 X1 Y2 Z3\nG43.4 H1\nG0 Z10\nG43.4 H2\nG49\nG0 Z20\n", c);
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 3u);
  expectEnd(r.motions[1], 1, 9, 10);  // tip: Y 2 + 7, Z as programmed
  EXPECT_NEAR(r.motions[1].start[kY], 9.0, 1e-12);
  expectEnd(r.motions[2], 1, 2, 20);  // joints again: Y back at 2, not the tip's 9
  EXPECT_NEAR(r.motions[2].start[kY], 2.0, 1e-12);
  // on (50), H1 -> H2 under G43.4 (off with 50, on with 75), off (75)
  EXPECT_EQ(calls, (std::vector<std::pair<double, bool>>{
                       {50, true}, {50, false}, {75, true}, {75, false}}));
}

TEST(InterpreterErrors, TcpSwitchTheKinematicsCannotMakeNamesTheWord) {
  InterpreterConfig c = baseConfig();
  c.tcp_switch = [](const AxisValues& m, double, bool to_tcp) {
    if (!to_tcp) throw std::runtime_error("the linear joints cannot reach that tip");
    return m;
  };
  const Result r = run("T1 M6\nG43.4 H1\nG0 X1\nG0 Z1 G49\n", c);
  ASSERT_TRUE(r.error);
  EXPECT_STREQ(r.error->what(), "Cannot leave G43.4 here: the linear joints cannot reach that tip");
  EXPECT_EQ(r.error->line(), 4);
  EXPECT_EQ(r.error->column(), 7);
}

TEST(Interpreter, TcpFlagIsSetOnMotions) {
  struct Flag : MotionSink {
    std::vector<bool> tcp;
    void motion(const Motion& m) override { tcp.push_back(m.tcp); }
  } sink;
  Interpreter interp(baseConfig(), sink);
  interp.run(makeStringSource("T1 M6\nG0 X1\nG43.4 H1\nG0 X2\nG49\nG0 X3\n"));
  EXPECT_EQ(sink.tcp, (std::vector<bool>{false, true, false}));
}

TEST(Interpreter, InverseTimeFeedIsTheRateTheMoveNeeds) {
  const Result r = run("G93 G1 X10 F2\nG1 A90 F4\nG2 X20 Y0 I5 J0 F1\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 3u);
  EXPECT_NEAR(r.motions[0].feed, 20.0, 1e-9);   // 10 mm in 1/2 min
  EXPECT_NEAR(r.motions[1].feed, 360.0, 1e-9);  // pure rotary: deg/min
  EXPECT_NEAR(r.motions[2].feed, 5 * M_PI, 1e-9);
}

TEST(Interpreter, ArcsInAllPlanesWithTurns) {
  const Result r =
      run("F100\nG0 X10\nG3 X10 Y0 Z-5 I-10 J0 P2\nG18 G0 X10 Y0 Z0\nG2 X0 Z10 I-10 K0\n"
          "G19 G0 X0 Y10 Z0\nG3 Y0 Z10 R10\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 6u);
  EXPECT_EQ(r.motions[1].turn, 2);
  EXPECT_EQ(r.motions[1].plane, Plane::kXY);
  EXPECT_NEAR(r.motions[1].center[0], 0.0, 1e-12);
  EXPECT_EQ(r.motions[3].plane, Plane::kXZ);
  EXPECT_EQ(r.motions[3].turn, -1);
  EXPECT_NEAR(r.motions[3].center[0], 0.0, 1e-12);  // Z
  EXPECT_NEAR(r.motions[3].center[1], 0.0, 1e-12);  // X
  EXPECT_EQ(r.motions[5].plane, Plane::kYZ);
  EXPECT_EQ(r.motions[5].turn, 1);
  // R10 from (Y10,Z0) to (Y0,Z10) ccw in YZ: the short arc's centre is (0,0)
  EXPECT_NEAR(r.motions[5].center[0], 0.0, 1e-9);
  EXPECT_NEAR(r.motions[5].center[1], 0.0, 1e-9);
  const Result bad = run("F100\nG2 X20 Y0 I5 J0\n");
  ASSERT_TRUE(bad.error);
  EXPECT_EQ(std::string(bad.error->what()).rfind("Radius to end of arc differs", 0), 0u);
}

TEST(Interpreter, CannedCycleInXZPlane) {
  // G18: the cycle drills along Y; X/Z position, R and the bottom are Y values.
  const Result r = run("G18 G0 X0 Y20 Z0\nG98 G81 X5 Z6 Y-4 R2 F50\nG80\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 5u);
  expectEnd(r.motions[1], 5, 20, 6);  // positioning at the initial level
  expectEnd(r.motions[2], 5, 2, 6);   // down to R
  expectEnd(r.motions[3], 5, -4, 6);  // feed to the bottom
  EXPECT_EQ(r.motions[3].type, MotionType::kFeed);
  expectEnd(r.motions[4], 5, 20, 6);  // G98: back to the initial level
}

TEST(Interpreter, CannedCycleIncrementalRepeats) {
  const Result r = run("G0 X0 Y0 Z10\nG91 G99 G81 X5 Z-4 R-8 L2 F50\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 1u + 4 + 3);
  expectEnd(r.motions[1], 5, 0, 10);
  expectEnd(r.motions[2], 5, 0, 2);
  expectEnd(r.motions[3], 5, 0, -2);
  expectEnd(r.motions[5], 10, 0, 2);
}

TEST(Interpreter, CutterCompEntryAndOutsideCorner) {
  const Result r =
      run("F100 T1 M6\nG0 X-10 Y0\nG41 D1 G1 X0 Y0\nG1 X10\nG1 Y-10\nG40 G1 X20 Y-20\n");
  ASSERT_FALSE(r.error) << r.error->what();
  // entry line, the corner arc at (10,0), the side, exit
  ASSERT_EQ(r.motions.size(), 6u);
  expectEnd(r.motions[1], 0, 3, 0);  // entry to the left of the first line
  EXPECT_EQ(r.motions[1].line, 4);   // released when line 4 was read
  expectEnd(r.motions[2], 10, 3, 0);
  EXPECT_EQ(r.motions[3].type, MotionType::kArc);  // round the convex corner
  EXPECT_EQ(r.motions[3].turn, -1);
  expectEnd(r.motions[3], 13, 0, 0);
  expectEnd(r.motions[4], 13, -10, 0);
  EXPECT_TRUE(r.motions[4].comp);
  expectEnd(r.motions[5], 20, -20, 0);
  EXPECT_FALSE(r.motions[5].comp);
}

TEST(Interpreter, CutterCompInsideCornerShortensTheMove) {
  const Result r = run("F100 T1 M6\nG0 X-10 Y0\nG42 D1 G1 X0 Y0\nG1 X10\nG1 Y-10\nG40 G0 X30\n");
  ASSERT_FALSE(r.error) << r.error->what();
  // right of X+ then turning right is an inside corner: no arc, lines meet at (7,-3)
  ASSERT_EQ(r.motions.size(), 5u);
  expectEnd(r.motions[1], 0, -3, 0);
  expectEnd(r.motions[2], 7, -3, 0);
  expectEnd(r.motions[3], 7, -10, 0);
  expectEnd(r.motions[4], 30, -10, 0);
  EXPECT_EQ(r.motions[4].type, MotionType::kRapid);
}

TEST(Interpreter, ProgramEndStopsReading) {
  const Result r = run("G0 X1\nM2\nG0 X5\n");
  ASSERT_FALSE(r.error);
  ASSERT_EQ(r.motions.size(), 1u);
  EXPECT_EQ(r.events.back().type, EventType::kProgramEnd);
}

TEST(Interpreter, PredefinedParametersAndPositionParameters) {
  const Result r = run("G20 G0 X1\n#1=#<_imperial>\n#2=#<_x>\n#3=#5420\nG21\nG0 X[#1*10+#2+#3]\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 2u);
  expectEnd(r.motions[1], 12, 0, 0);  // 1*10 + 1 + 1
}

// Values rs274 2.9 gives (checked against it by hand, DEBUG messages): mdhd had
// _vmajor 2 / _vminor 9, _feed_hold 0, overrides fixed at 1, and no _line,
// _call_level or _remap_level.
TEST(Interpreter, PredefinedVersionLineCallLevelAndOverrideSwitches) {
  const Result r =
      run("#1=#<_vmajor>\n"         // 1
          "#2=#<_vminor>\n"         // 2
          "#3=#<_line>\n"           // 3
          "o<s> sub\n"              // 4
          "  #31=#<_call_level>\n"  // 5
          "  #32=#<_line>\n"        // 6
          "o<s> endsub\n"           // 7
          "o<s> call\n"             // 8
          "#6=#<_call_level>\n"     // 9
          "#7=[#<_feed_hold>*1000 + #<_feed_override>*100 + #<_speed_override>*10 + "
          "#<_adaptive_feed>]\n"  // 10
          "M49\n"
          "M52 P1\n"
          "M53 P0\n"
          "#8=[#<_feed_hold>*1000 + #<_feed_override>*100 + #<_speed_override>*10 + "
          "#<_adaptive_feed>]\n"
          "M48\n"
          "M50 P0\n"
          "#9=[#<_feed_hold>*1000 + #<_feed_override>*100 + #<_speed_override>*10 + "
          "#<_adaptive_feed> + #<_remap_level>]\n"
          "G0 X0\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.param(1), 2.9);
  EXPECT_EQ(r.param(2), 0.0);
  EXPECT_EQ(r.param(3), 3.0);
  EXPECT_EQ(r.param(31), 1.0);  // #1..#30 are the sub's own
  EXPECT_EQ(r.param(32), 6.0);
  EXPECT_EQ(r.param(6), 0.0);
  EXPECT_EQ(r.param(7), 1110.0);  // feed hold on, both overrides on, adaptive feed off
  EXPECT_EQ(r.param(8), 1.0);     // M49: overrides off; M52 P1, M53 P0
  EXPECT_EQ(r.param(9), 11.0);    // M48 then M50 P0: the feed override off again
}

TEST(ToolTable, ParsesLinuxCncFormat) {
  const ToolTable t = parseToolTable("; comment\nT1 P1 Z50.8 D6.35 ;mill\nT7 P5 Z1 D0.5\n", 25.4);
  ASSERT_EQ(t.entries().size(), 2u);
  EXPECT_DOUBLE_EQ(t.find(1)->length, 50.8 * 25.4);
  EXPECT_DOUBLE_EQ(t.find(7)->diameter, 0.5 * 25.4);
  EXPECT_EQ(t.find(3), nullptr);
  EXPECT_THROW(parseToolTable("T1 Zabc\n"), GcodeError);
}

}  // namespace
}  // namespace mdhd::gcode::testing

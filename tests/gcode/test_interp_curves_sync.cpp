// Splines (G5, G5.1, G5.2/G5.3), spindle-synchronised moves (G33, G33.1),
// the probe model, LinuxCNC's unused-word errors and the initial retract mode.
#include <gtest/gtest.h>

#include <cmath>

#include "oracle_support.h"
#include "sim/gcode/spline_math.h"

namespace mdhd::gcode::testing {
namespace {

using Result = ProgramRun;

Result runPlain(const std::string& program, InterpreterConfig config = {}) {
  return runProgram(program, std::move(config));
}

std::string errorOf(const std::string& program) {
  const Result r = runPlain(program);
  return r.error ? r.error->what() : std::string("(no error)");
}

// Distance from q to the polyline of the motions [first, last).
double polylineDistance(const std::vector<RecordedMotion>& ms, double qx, double qy) {
  double best = 1e300;
  for (const RecordedMotion& m : ms) {
    const double ax = m.start[kX], ay = m.start[kY], bx = m.end[kX], by = m.end[kY];
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? ((qx - ax) * dx + (qy - ay) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, std::hypot(qx - ax - t * dx, qy - ay - t * dy));
  }
  return best;
}

// ---------------------------------------------------------------- G5.1

// G5.1 from (0,0), I10 J0, to (10,10): the quadratic Bezier with control
// points (0,0) (10,0) (10,10): B(t) = (20t - 10t^2, 10t^2).
TEST(Splines, QuadraticFollowsTheCurveWithinTolerance) {
  const Result r = runPlain("G21 G17 G90 F600\nG0 X0 Y0 Z1\nG5.1 X10 Y10 I10 J0\nG1 X20\n");
  ASSERT_FALSE(r.error) << r.error->what();
  std::vector<RecordedMotion> curve;
  for (const RecordedMotion& m : r.motions)
    if (m.line == 3) curve.push_back(m);
  ASSERT_GE(curve.size(), 8u);
  EXPECT_LT(curve.size(), 400u);  // 0.001 mm on a ~16 mm curve
  const double tol = 0.001;
  // Every vertex lies on the curve (the polyline is inscribed)...
  for (const RecordedMotion& m : curve) {
    const double t = std::sqrt(m.end[kY] / 10.0);
    EXPECT_NEAR(m.end[kX], 20 * t - 10 * t * t, 1e-9);
    EXPECT_EQ(m.type, MotionType::kFeed);
    EXPECT_DOUBLE_EQ(m.end[kZ], 1.0);
    EXPECT_DOUBLE_EQ(m.feed, 600.0);
  }
  // ... and the curve is never farther than the tolerance from it.
  double worst = 0.0;
  for (int i = 0; i <= 4000; ++i) {
    const double t = i / 4000.0;
    worst = std::max(worst, polylineDistance(curve, 20 * t - 10 * t * t, 10 * t * t));
  }
  EXPECT_LE(worst, tol);
  EXPECT_GT(worst, tol / 100);  // not absurdly fine either
  // Ends exactly at the programmed point; the next move starts there.
  EXPECT_EQ(curve.back().end[kX], 10.0);
  EXPECT_EQ(curve.back().end[kY], 10.0);
  EXPECT_EQ(r.motions.back().start, curve.back().end);
  EXPECT_DOUBLE_EQ(r.motions.back().end[kX], 20.0);
}

TEST(Splines, ToleranceSetsTheNumberOfMoves) {
  auto movesFor = [](double tol) {
    InterpreterConfig c;
    c.spline_tolerance = tol;
    return runPlain("F100\nG5.1 X10 Y10 I10 J0\n", c).motions.size();
  };
  EXPECT_GT(movesFor(0.0001), 2 * movesFor(0.01));
  InterpreterConfig bad;
  bad.spline_tolerance = 0.0;
  RecordingSink sink;
  EXPECT_THROW(Interpreter(bad, sink), GcodeError);
}

// ---------------------------------------------------------------- G5

TEST(Splines, CubicChainsContinueTheEndDirection) {
  // First cubic: (0,0) -> (10,0), leaving along +Y (I0 J5), arriving from +Y
  // (P0 Q5: last control point 5 above the end). The second, without I J,
  // leaves (10,0) along -P -Q = (0,-5): straight down.
  const Result r = runPlain("F100\nG5 X10 Y0 I0 J5 P0 Q5\nG5 X20 Y0 P0 Q-5\n");
  ASSERT_FALSE(r.error) << r.error->what();
  std::vector<RecordedMotion> a, b;
  for (const RecordedMotion& m : r.motions) (m.line == 2 ? a : b).push_back(m);
  ASSERT_GE(a.size(), 4u);
  ASSERT_GE(b.size(), 4u);
  EXPECT_EQ(a.back().end[kX], 10.0);
  EXPECT_EQ(b.back().end[kX], 20.0);
  // Bezier (0,0) (0,5) (10,5) (10,0) at t = 1/2: (5, 3.75), the top.
  EXPECT_NEAR(polylineDistance(a, 5.0, 3.75), 0.0, 0.001);
  // Leaves (10,0) going down (-Y), bottom at (15, -3.75).
  EXPECT_NEAR(b.front().end[kX] - 10.0, 0.0, 0.05);
  EXPECT_LT(b.front().end[kY], 0.0);
  EXPECT_NEAR(polylineDistance(b, 15.0, -3.75), 0.0, 0.001);
  // The whole first curve is on the upper side, the second on the lower.
  for (const RecordedMotion& m : a) EXPECT_GE(m.end[kY], -1e-12);
  for (const RecordedMotion& m : b) EXPECT_LE(m.end[kY], 1e-12);
}

TEST(Splines, ErrorsInLinuxCncWords) {
  EXPECT_EQ(errorOf("F100\nG5.1 X1 Y1 I1\n"), "Must specify both I and J with G5.1");
  EXPECT_EQ(errorOf("F100\nG5 X1 Y1 I1 J1 P1\n"), "Must specify both P and Q with G5");
  EXPECT_EQ(errorOf("F100\nG5 X1 Y1 I1 P1 Q1\n"), "Must specify both I and J, or neither");
  EXPECT_EQ(errorOf("F100\nG18\nG5.1 X1 Y1 I1 J1\n"), "Splines must be in the XY plane");
  EXPECT_EQ(errorOf("F100\nG5.1 X1 Y1 Z1 I1 J1\n"), "Splines may not have motion in Z, A, B, or C");
  EXPECT_EQ(errorOf("G5.1 X1 Y1 I1 J1\n"), "Cannot make arc with zero feed rate");
  EXPECT_EQ(errorOf("G93\nG5.1 X1 Y1 I1 J1\n"), "F word missing with inverse time arc move");
  EXPECT_EQ(errorOf("F100\nG5.3\n"), "Cannot use G5.3 without G5.2 first");
  EXPECT_EQ(errorOf("F100\nG5.2 X1 Y1 P1 L4\nX2 Y0 P1\nG5.3\n"),
            "You must specify a number of control points at least equal to the order L = 4");
  EXPECT_EQ(errorOf("F100\nG5.2 X1 P1\n"),
            "You must specify both X and Y coordinates for Control Points");
  EXPECT_EQ(errorOf("F100\nG5.2 X1 Y1 P1\nX2 Y2\n"),
            "Must specify positive weight P for every Control Point");
  EXPECT_EQ(errorOf("G5.2 X1 Y1 P1\n"), "Cannot make a NURBS with 0 feedrate");
  EXPECT_EQ(errorOf("F100\nG5.2 X1 Y1 P1 L[10**300]\n"), "NURBS order L above 64");
  EXPECT_EQ(errorOf("T0\nG41.1 D2\nF100\nG5.1 X1 Y1 I1 J1\n"),
            "Cannot convert spline with cutter radius compensation");
}

// ---------------------------------------------------------------- G5.2 / G5.3

// A quarter circle is a rational quadratic: (10,0) w1, (10,10) w=sqrt(2)/2,
// (0,10) w1. Every vertex must lie on the circle of radius 10.
TEST(Splines, NurbsQuarterCircleIsExact) {
  const Result r =
      runPlain("F100\nG0 X10 Y0\nG5.2 X10 Y10 P0.70710678118654752 L3\nX0 Y10 P1\nG5.3\nG1 X-5\n");
  ASSERT_FALSE(r.error) << r.error->what();
  std::vector<RecordedMotion> arc;
  for (const RecordedMotion& m : r.motions)
    if (m.line == 5) arc.push_back(m);
  ASSERT_GE(arc.size(), 8u);
  for (const RecordedMotion& m : arc) {
    EXPECT_NEAR(std::hypot(m.end[kX], m.end[kY]), 10.0, 1e-9);
    // Chord midpoints: the sagitta is within the tolerance.
    const double mx = (m.start[kX] + m.end[kX]) / 2, my = (m.start[kY] + m.end[kY]) / 2;
    EXPECT_GE(std::hypot(mx, my), 10.0 - 0.001);
  }
  EXPECT_EQ(arc.back().end[kX], 0.0);
  EXPECT_EQ(arc.back().end[kY], 10.0);
  // Nothing moved while the points were collected; G5.3 ends the mode.
  EXPECT_EQ(r.motions.size(), arc.size() + 2);
  EXPECT_EQ(r.motions.back().line, 6);
  EXPECT_EQ(errorOf("F100\nG5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3\nX5\n"),
            "Cannot use axis values without a g code that uses them");
}

TEST(Splines, NurbsOfHigherOrderEndsAtItsLastPoint) {
  const Result r = runPlain("F100\nG5.2 X0 Y10 P1 L4\nX10 Y10 P2\nX10 Y0 P1\nX20 Y0 P1\nG5.3\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_FALSE(r.motions.empty());
  EXPECT_EQ(r.motions.back().end[kX], 20.0);
  EXPECT_EQ(r.motions.back().end[kY], 0.0);
  EXPECT_EQ(r.state.current[kX], 20.0);
}

// A rejected block leaves the collected control points as they were.
TEST(Splines, RejectedBlockKeepsTheNurbsPoints) {
  RecordingSink sink;
  BlockExecutor ex(InterpreterConfig{}, sink);
  int line = 0;
  auto block = [&line](std::vector<Word> words) {
    Block b;
    b.pos.line = ++line;
    b.words = std::move(words);
    return b;
  };
  ex.execute(block({{'F', 100, 1}}));
  ex.execute(block({{'G', 5.2, 1}, {'X', 0, 2}, {'Y', 10, 3}, {'P', 1, 4}}));
  EXPECT_THROW(ex.execute(block({{'X', 50, 1}, {'Y', 50, 2}})), GcodeError);  // no P
  // A rejected block of another motion leaves the G5.2 collection going on.
  EXPECT_THROW(ex.execute(block({{'G', 5.1, 1}, {'X', 1, 2}, {'Y', 1, 3}, {'I', 1, 4}})),
               GcodeError);
  ex.execute(block({{'X', 10, 1}, {'Y', 0, 2}, {'P', 1, 3}}));
  ex.execute(block({{'G', 5.3, 1}}));
  ASSERT_FALSE(sink.motions.empty());
  // The curve of (0,0) (0,10) (10,0): B(1/2) = (2.5, 5), and nothing of (50,50).
  EXPECT_NEAR(polylineDistance(sink.motions, 2.5, 5.0), 0.0, 0.001);
  for (const RecordedMotion& m : sink.motions) EXPECT_LE(m.end[kX], 10.0);
  EXPECT_EQ(sink.motions.back().end[kX], 10.0);
  EXPECT_EQ(sink.motions.back().end[kY], 0.0);
}

TEST(SplineMath, ClampedCurveInterpolatesItsEnds) {
  const NurbsCurve c({{0, 0, 1}, {1, 2, 1}, {3, 2, 0.5}, {4, 0, 1}, {6, 1, 1}}, 3);
  EXPECT_DOUBLE_EQ(c.uMax(), 3.0);
  EXPECT_NEAR(c.at(0)[0], 0.0, 1e-12);
  EXPECT_NEAR(c.at(3)[0], 6.0, 1e-12);
  EXPECT_NEAR(c.at(3)[1], 1.0, 1e-12);
}

// ---------------------------------------------------------------- G33 / G33.1

TEST(SpindleSync, RigidTapGoesInAndComesBackOut) {
  const Result r = runPlain("G20\nS200 M3\nG0 X1 Y2 Z0.25\nG33.1 Z-0.95 K0.05\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 3u);
  const RecordedMotion& in = r.motions[1];
  const RecordedMotion& out = r.motions[2];
  EXPECT_EQ(in.type, MotionType::kFeed);
  EXPECT_TRUE(in.sync);
  EXPECT_NEAR(in.feed, 1.27, 1e-12);  // K0.05 inch per revolution
  EXPECT_NEAR(in.end[kZ], -0.95 * 25.4, 1e-9);
  EXPECT_NEAR(in.end[kX], 25.4, 1e-9);
  EXPECT_EQ(out.end, in.start);
  EXPECT_TRUE(out.sync);
  EXPECT_NEAR(r.state.current[kZ], 0.25 * 25.4, 1e-9);  // LinuxCNC: same spot after the tap
}

TEST(SpindleSync, G33IsOneSynchronisedMove) {
  const Result r = runPlain("S100 M4\nG33 Z-10 K1.5\n");
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 1u);
  EXPECT_TRUE(r.motions[0].sync);
  EXPECT_DOUBLE_EQ(r.motions[0].feed, 1.5);
  EXPECT_DOUBLE_EQ(r.state.current[kZ], -10.0);
}

TEST(SpindleSync, Errors) {
  EXPECT_EQ(errorOf("G33.1 Z-1 K1\n"), "Spindle not turning in G33.1");
  EXPECT_EQ(errorOf("G33 Z-1 K1\n"), "Spindle not turning in G33");
  EXPECT_EQ(errorOf("S100 M3\nG33.1 Z-1\n"), "K word missing with g33");
  EXPECT_EQ(errorOf("S100 M3\nG33.1 Z-1 K1 F10\n"), "F word used with a g33");
  EXPECT_EQ(errorOf("S100 M3\nG33.1 Z-1 A10 K1\n"), "G33.1 moves only X, Y and Z");
}

// ---------------------------------------------------------------- probe model

TEST(Probe, ModelDecidesWhereTheMoveEnds) {
  InterpreterConfig c;
  c.probe_stop = [](const AxisValues& start, const AxisValues& target, AxisValues& stop) {
    stop = target;
    stop[kZ] = (start[kZ] + target[kZ]) / 2;  // trips half way down
    return true;
  };
  const Result r = runPlain("G0 Z10\nG38.2 Z-10 F100\nG91 G0 Z1\n", c);
  ASSERT_FALSE(r.error) << r.error->what();
  ASSERT_EQ(r.motions.size(), 3u);
  EXPECT_DOUBLE_EQ(r.motions[1].end[kZ], 0.0);
  EXPECT_DOUBLE_EQ(r.motions[2].end[kZ], 1.0);
  EXPECT_DOUBLE_EQ(r.param(5063), 0.0);  // #5063
  EXPECT_DOUBLE_EQ(r.param(5070), 1.0);  // #5070: tripped
  // Without a model the move runs to the target and #5070 says it did not trip.
  const Result none = runPlain("G0 Z10\nG38.3 Z-10 F100\n");
  EXPECT_DOUBLE_EQ(none.motions[1].end[kZ], -10.0);
  EXPECT_DOUBLE_EQ(none.param(5063), -10.0);
  EXPECT_DOUBLE_EQ(none.param(5070), 0.0);
}

// ---------------------------------------------------------------- words, modes

TEST(WordChecks, UnusedWordsInLinuxCncWords) {
  EXPECT_EQ(errorOf("G0 X1 P2\n"),
            "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 "
            "M63 M64 M65 M66 or user M code to use it");
  EXPECT_EQ(errorOf("G1 X1 Q1 F100\n"),
            "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that "
            "uses it");
  EXPECT_EQ(errorOf("G1 X1 E1 F100\n"), "E word with no G76, M66, M67 or M68 to use it");
  EXPECT_EQ(errorOf("G1 X1 I1 F100\n"),
            "I word with no G2, G3, G5, G5.1, G10, G76, or G87 to use it");
  EXPECT_EQ(errorOf("G1 X1 H1 F100\n"), "H word with no G43 or G76 to use it");
  EXPECT_EQ(errorOf("G1 X1 D1 F100\n"), "D word with no G41, G41.1, G42, G42.1, or G96 to use it");
  EXPECT_EQ(errorOf("G0 X1 L1\n"),
            "L word with no G10, cutter compensation, canned cycle, digital/analog input, or "
            "NURBS code");
  EXPECT_EQ(errorOf("F100\nG2 X1 Y1 I1 P1.5\n"), "P value not an integer with M19 G2 or G3");
  EXPECT_EQ(errorOf("F100\nG2 X1 Y1 I1 P0\n"), "P value should be 1 or greater with G2 or G3");
  EXPECT_EQ(errorOf("F100\nG81 X1 Y1 Z-1 R1 A5\n"), "Cannot put an a in canned cycle");
  EXPECT_EQ(errorOf("G4 P1\nG64 P0.01 Q0.01\nG0 X1\n"), "(no error)");
}

// LinuxCNC starts in R_PLANE (G99): a cycle without G98/G99 retracts to R.
TEST(Modes, CyclesRetractToRUnlessG98) {
  Result r = runPlain("F100\nG0 Z10\nG81 X0 Y0 Z-1 R2\n");
  ASSERT_FALSE(r.error) << r.error->what();
  EXPECT_DOUBLE_EQ(r.motions.back().end[kZ], 2.0);
  r = runPlain("F100\nG0 Z10\nG98 G81 X0 Y0 Z-1 R2\n");
  EXPECT_DOUBLE_EQ(r.motions.back().end[kZ], 10.0);
}

}  // namespace
}  // namespace mdhd::gcode::testing

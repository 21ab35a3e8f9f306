// Durations of interpreted motions, worked out by hand.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sim/kinematics/motion_time.h"
#include "sim/kinematics/presets.h"

namespace mdhd::kin {
namespace {

using gcode::FeedMode;
using gcode::Motion;
using gcode::MotionType;
constexpr double kPi = std::numbers::pi;

Kinematics machine(Machine m, double rapid, double max_feed) {
  m.rapid_feed = rapid;
  m.max_feed = max_feed;
  return Kinematics(std::move(m));
}

Motion move(MotionType type, gcode::AxisValues start, gcode::AxisValues end, double feed = 0.0) {
  Motion m;
  m.type = type;
  m.start = start;
  m.end = end;
  m.feed = feed;
  return m;
}

// XYZABCUVW
gcode::AxisValues at(double x, double y, double z, double a = 0, double c = 0) {
  return {x, y, z, a, 0, c, 0, 0, 0};
}

TEST(MotionTime, RapidTakesAsLongAsTheSlowestJoint) {
  const Kinematics mill = machine(presets::threeAxisMill(), 15000, 8000);
  // 40 mm on Y is the longest travel: 40 / 15000 min = 0.16 s
  EXPECT_DOUBLE_EQ(motionSeconds(move(MotionType::kRapid, at(0, 0, 0), at(30, 40, 0)), mill, 50),
                   0.16);
  const Kinematics ac = machine(presets::acTrunnion(), 20000, 10000);
  // C turns 180 degrees at 20000 deg/min: 0.54 s; X's 10 mm and A's 90 degrees are shorter
  EXPECT_DOUBLE_EQ(
      motionSeconds(move(MotionType::kRapid, at(0, 0, 0), at(10, 0, 0, -90, 180)), ac, 50), 0.54);
  EXPECT_EQ(motionSeconds(move(MotionType::kRapid, at(1, 2, 3), at(1, 2, 3)), ac, 50), 0.0);
}

// Under G43.4 with the tip 200 mm off the C axis, X = 200 cos C and Y = 200 sin C in the
// machine. A rapid half turn moves X 400 mm (Y 0 -> 200 -> 0: 400 too): 1.2 s at
// 20000 mm/min. A full turn ends where it started, but X and Y each travel 4 x 200 =
// 800 mm: 2.4 s. It was 1.08 s (C's 360 degrees), faster than the half turn.
TEST(MotionTime, TcpRapidCountsTheJointsWholePath) {
  const Kinematics ac = machine(presets::acTrunnion(), 20000, 10000);
  Motion half = move(MotionType::kRapid, at(200, 0, 0), at(200, 0, 0, 0, 180));
  half.tcp = true;
  EXPECT_NEAR(motionSeconds(half, ac, 50), 1.2, 1e-9);
  Motion full = half;
  full.end = at(200, 0, 0, 0, 360);
  EXPECT_NEAR(motionSeconds(full, ac, 50), 2.4, 1e-9);
  // Tilting A -90 -> 0 with the tip at (0, 0, 100) in W: the tip in the machine is
  // R_x(A) (0, 0, 100) = (0, -100 sin A, 100 cos A): Y 100 -> 0, Z 0 -> 100 (+50 of
  // tool), each 100 mm, monotonic: 0.3 s, the same as end - start.
  Motion tilt = move(MotionType::kRapid, at(0, 0, 100, -90), at(0, 0, 100, 0));
  tilt.tcp = true;
  EXPECT_NEAR(motionSeconds(tilt, ac, 50), 0.3, 1e-9);
}

TEST(MotionTime, FeedOverTheLinearPathCappedAtMaxFeed) {
  const Kinematics ac = machine(presets::acTrunnion(), 20000, 10000);
  // 3-4-5: 50 mm at 600 mm/min = 5 s
  EXPECT_DOUBLE_EQ(motionSeconds(move(MotionType::kFeed, at(0, 0, 0), at(30, 40, 0), 600), ac, 50),
                   5.0);
  // F20000 is capped at max_feed 10000: 50 mm in 0.3 s
  EXPECT_DOUBLE_EQ(
      motionSeconds(move(MotionType::kFeed, at(0, 0, 0), at(30, 40, 0), 20000), ac, 50), 0.3);
  // With X Y Z moving the rotaries follow along: 60 mm at 600 = 6 s
  EXPECT_DOUBLE_EQ(
      motionSeconds(move(MotionType::kFeed, at(0, 0, 0), at(60, 0, 0, 90, 45), 600), ac, 50), 6.0);
  // Pure rotary: sqrt(30^2 + 40^2) = 50 degrees at 500 deg/min = 6 s
  EXPECT_DOUBLE_EQ(
      motionSeconds(move(MotionType::kFeed, at(5, 5, 5, 0, 0), at(5, 5, 5, 30, 40), 500), ac, 50),
      6.0);
  EXPECT_EQ(motionSeconds(move(MotionType::kFeed, at(5, 5, 5), at(5, 5, 5), 500), ac, 50), 0.0);
}

Motion arc(gcode::Plane plane, gcode::AxisValues start, gcode::AxisValues end, double c0, double c1,
           int turn, double feed) {
  Motion m = move(MotionType::kArc, start, end, feed);
  m.plane = plane;
  m.center = {c0, c1};
  m.turn = turn;
  return m;
}

TEST(MotionTime, ArcsAlongTheirHelicalLength) {
  const Kinematics mill = machine(presets::threeAxisMill(), 15000, 8000);
  // Quarter circle R10 ccw in XY: 5 pi mm at 600 mm/min = pi / 2 s
  const Motion quarter = arc(gcode::Plane::kXY, at(10, 0, 0), at(0, 10, 0), 0, 0, 1, 600);
  EXPECT_NEAR(motionSeconds(quarter, mill, 50), kPi / 2, 1e-12);
  EXPECT_NEAR(feedPathLength(quarter, mill, 50), 5 * kPi, 1e-12);
  // The same ends clockwise: three quarters, 15 pi mm
  EXPECT_NEAR(
      feedPathLength(arc(gcode::Plane::kXY, at(10, 0, 0), at(0, 10, 0), 0, 0, -1, 600), mill, 50),
      15 * kPi, 1e-12);
  // Full helix turn R10 dropping 5 mm: sqrt((20 pi)^2 + 25); P2 adds a turn
  const Motion helix = arc(gcode::Plane::kXY, at(10, 0, 0), at(10, 0, -5), 0, 0, 1, 600);
  EXPECT_NEAR(feedPathLength(helix, mill, 50), std::hypot(20 * kPi, 5), 1e-9);
  const Motion helix2 = arc(gcode::Plane::kXY, at(10, 0, 0), at(10, 0, -5), 0, 0, 2, 600);
  EXPECT_NEAR(feedPathLength(helix2, mill, 50), std::hypot(40 * kPi, 5), 1e-9);
  // G18: the centre is (Z, X); quarter from X10 Z0 to X0 Z10 about the origin
  EXPECT_NEAR(
      feedPathLength(arc(gcode::Plane::kXZ, at(10, 0, 0), at(0, 0, 10), 0, 0, -1, 600), mill, 50),
      5 * kPi, 1e-12);
  // G19 half circle R5 in YZ with X moving 0: 5 pi
  EXPECT_NEAR(
      feedPathLength(arc(gcode::Plane::kYZ, at(0, 5, 0), at(0, -5, 0), 0, 0, 1, 600), mill, 50),
      5 * kPi, 1e-12);
  // Spiral from radius 10 to 20 over a half turn: mean radius 15 * pi
  EXPECT_NEAR(
      feedPathLength(arc(gcode::Plane::kXY, at(10, 0, 0), at(-20, 0, 0), 0, 0, 1, 600), mill, 50),
      15 * kPi, 1e-12);
}

TEST(MotionTime, InverseTimeAndPerRevolution) {
  const Kinematics mill = machine(presets::threeAxisMill(), 15000, 8000);
  Motion g93 = move(MotionType::kFeed, at(0, 0, 0), at(30, 40, 0), 100);
  g93.feed_mode = FeedMode::kInverseTime;
  g93.inverse_time = 2.0;  // F2: half a minute
  EXPECT_DOUBLE_EQ(motionSeconds(g93, mill, 50), 30.0);
  g93.end = at(8000, 0, 0);  // 8000 mm cannot take less than a minute at max_feed 8000
  EXPECT_DOUBLE_EQ(motionSeconds(g93, mill, 50), 60.0);
  g93.inverse_time = 0.0;
  EXPECT_THROW(motionSeconds(g93, mill, 50), MotionTimeError);

  Motion g95 = move(MotionType::kFeed, at(0, 0, 0), at(30, 40, 0), 0.1);  // 0.1 mm/rev
  g95.feed_mode = FeedMode::kUnitsPerRevolution;
  g95.spindle = gcode::SpindleState::kClockwise;
  g95.spindle_rpm = 1000;  // 100 mm/min: 50 mm in 30 s
  EXPECT_DOUBLE_EQ(motionSeconds(g95, mill, 50), 30.0);
  g95.spindle = gcode::SpindleState::kOff;
  EXPECT_THROW(motionSeconds(g95, mill, 50), MotionTimeError);
}

TEST(MotionTime, BadFeedsAndEvents) {
  const Kinematics mill = machine(presets::threeAxisMill(), 15000, 8000);
  EXPECT_THROW(motionSeconds(move(MotionType::kFeed, at(0, 0, 0), at(1, 0, 0), 0), mill, 50),
               MotionTimeError);
  gcode::Event dwell;
  dwell.type = gcode::EventType::kDwell;
  dwell.value = 2.5;
  EXPECT_EQ(eventSeconds(dwell), 2.5);
  gcode::Event change;
  change.type = gcode::EventType::kToolChange;
  change.value = 7;
  EXPECT_EQ(eventSeconds(change), 0.0);
}

}  // namespace
}  // namespace mdhd::kin

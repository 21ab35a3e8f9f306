// The program track (placing a reported line on a motion), the look-ahead's time
// to contact, and the event log the SSE streams read.
#include <thread>

#include <gtest/gtest.h>

#include "daemon/shadow_events.h"
#include "daemon/shadow_lookahead.h"
#include "sim/kinematics/motion_time.h"
#include "tests/shadow/shadow_fixture.h"

namespace mdhd::shadow {
namespace {

using namespace std::chrono_literals;
using testing::cellJob;

constexpr const char* kStart = "G21 G90 G17\nT1 M6\nG43 H1\nM3 S9000\n";  // lines 1-4

TEST(ProgramTrack, PlacesLinesOnMotionsThroughLoopsAndCannedCycles) {
  const protocol::Job job = cellJob(std::string(kStart) +
                                    "#1 = 0\n"                     // 5
                                    "o100 while [#1 LT 2]\n"       // 6
                                    "G0 X[10 + #1 * 10] Y10 Z5\n"  // 7
                                    "G1 Z-1 F300\n"                // 8
                                    "#1 = [#1 + 1]\n"              // 9
                                    "o100 endwhile\n"              // 10
                                    "G81 X30 Y30 Z-3 R2 F100\n"    // 11: rapid, feed, rapid
                                    "G80\nM5\nM30\n");
  const kin::Kinematics kin(*job.machine);
  const ProgramTrack track(job, kin);
  ASSERT_GE(track.size(), 4u + 3u);
  EXPECT_EQ(track.blockText(8), "G1 Z-1 F300");
  EXPECT_EQ(track.blockText(99), "");
  gcode::AxisValues q{};
  // The loop's second pass: line 7 again, found after the first pass's motions.
  const auto first = track.locate(7, q, 0);
  ASSERT_TRUE(first);
  const auto second = track.locate(7, q, *first + 1);
  ASSERT_TRUE(second);
  EXPECT_GT(*second, *first);
  EXPECT_EQ(track.at(*second).motion.end[gcode::kX], 20.0);
  // Past the last pass of a line, the program started again: its first pass.
  EXPECT_EQ(track.locate(7, q, track.size() - 1), first);
  EXPECT_FALSE(track.locate(9, q, 0));  // no motion on that line
  // The canned cycle: the motion whose chord passes closest to the pose.
  const auto cycle = track.locate(11, q, 0);
  ASSERT_TRUE(cycle);
  std::size_t feed = *cycle;
  while (track.at(feed).motion.type != gcode::MotionType::kFeed) ++feed;
  gcode::AxisValues mid = track.at(feed).motion.start;
  mid[gcode::kZ] =
      0.5 * (track.at(feed).motion.start[gcode::kZ] + track.at(feed).motion.end[gcode::kZ]);
  EXPECT_EQ(track.locate(11, mid, *cycle), feed);
}

TEST(LookAhead, PredictsARapidIntoTheStockWithItsTimeToContact) {
  const protocol::Job job = cellJob(std::string(kStart) +
                                    "G0 X10 Y10 Z5\n"  // 5
                                    "G1 X20 F600\n"    // 6: 10 mm at 600 mm/min, 1 s
                                    "G0 Z-1\n"         // 7: 5 of its 6 mm in the air
                                    "G0 Z5\nM5\nM30\n");
  const kin::Kinematics kin(*job.machine);
  const ProgramTrack track(job, kin);
  ShadowCarver carver(job, kin, &track);
  const auto index = track.locate(6, {}, 0);
  ASSERT_TRUE(index);
  // The machine is 4 mm into line 6: 0.6 s left of it.
  gcode::AxisValues q = track.at(*index).motion.start;
  q[gcode::kX] += 4.0;
  auto ahead = carver.simulation().fork();
  std::vector<PredictedContact> found;
  const std::size_t simulated = lookAhead(*ahead, track, kin, *index, q, LookaheadSpan{},
                                          [&](const PredictedContact& p) { found.push_back(p); });
  EXPECT_GE(simulated, 2u);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].collision.type, check::CollisionType::kRapidIntoStock);
  EXPECT_EQ(found[0].collision.line, 7);
  EXPECT_EQ(found[0].collision.block, "G0 Z-1");
  EXPECT_EQ(found[0].motion, *index + 1);
  const double rapid = track.at(*index + 1).seconds;
  EXPECT_NEAR(found[0].seconds, 0.6 + rapid * 5.0 / 6.0, rapid * 0.2 / 6.0 + 1e-9);
  EXPECT_DOUBLE_EQ(carver.simulation().stock().volume(),
                   40.0 * 40 * 20);  // the live stock is untouched
  // The rest of a motion at its end is nothing.
  EXPECT_FALSE(restOfMotion(track.at(*index), kin, track.at(*index).motion.end));
}

TEST(EventLog, ReadersFollowByIdWaitBoundedAndSeeDrops) {
  EventLog log(4);
  EXPECT_TRUE(log.since(0, 1ms).empty());
  std::thread writer([&] {
    std::this_thread::sleep_for(20ms);
    log.publish("pose", {{"n", 1}});
  });
  const auto t0 = std::chrono::steady_clock::now();
  const auto got = log.since(0, 2s);  // wakes on the publish, not after 2 s
  writer.join();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 1s);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].id, 1u);
  EXPECT_EQ(got[0].type, "pose");
  EXPECT_EQ(got[0].data, "{\"n\":1}");
  for (int i = 2; i <= 7; ++i) log.publish("alarm", {{"n", i}});
  bool missed = false;
  const auto later = log.since(1, 0ms, &missed);
  EXPECT_TRUE(missed);  // ids 2 and 3 left the ring of 4
  ASSERT_EQ(later.size(), 4u);
  EXPECT_EQ(later.front().id, 4u);
  EXPECT_EQ(log.lastId(), 7u);
  log.close();
  EXPECT_TRUE(log.closed());
  const auto t1 = std::chrono::steady_clock::now();
  EXPECT_TRUE(log.since(7, 2s).empty());  // closed: at once
  EXPECT_LT(std::chrono::steady_clock::now() - t1, 1s);
}

}  // namespace
}  // namespace mdhd::shadow

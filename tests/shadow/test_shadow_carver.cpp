// ShadowCarver: polled samples as straight joint-space motions, cut and checked
// by the engine; straight runs merged, standing still and resyncs cut nothing,
// the kind of move taken from the program at the reported line.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "tests/shadow/shadow_fixture.h"

namespace mdhd::shadow {
namespace {

using testing::at;
using testing::cellJob;

// Line 6 rapids 1 mm into the stock; the polls follow the program line by line.
protocol::Job rapidIntoStockJob() {
  return cellJob(
      "G21 G90 G17\nT1 M6\nG43 H1\nM3 S9000\n"  // 1-4
      "G0 X10 Y10 Z5\n"                         // 5
      "G0 Z-1\n"                                // 6: a rapid into the stock
      "G1 Z-2 F300\n"                           // 7
      "G0 Z5\nM5\nM30\n");
}

std::vector<PollSample> rapidIntoStockSamples() {
  return {at(10, 10, 5, 0, 5), at(10, 10, 2, 2, 6), at(10, 10, -1, 4, 6), at(10, 10, -2, 200, 7),
          at(10, 10, 5, 210, 8)};
}

using std::numbers::pi;

TEST(ShadowCarver, SamplesOnAStraightLineAreOneMotionAndCutTheSlot) {
  const protocol::Job job = cellJob();
  const kin::Kinematics kin(*job.machine);
  ShadowCarver carver(job, kin, nullptr);
  const double full = carver.simulation().stock().volume();
  std::vector<PollSample> batch{at(10, 10, 5, 0), at(10, 10, -2, 10)};             // plunge
  for (int i = 1; i <= 20; ++i) batch.push_back(at(10 + i, 10, -2, 10 + 10 * i));  // slot along x
  const CarveResult r = carver.carve(batch);
  EXPECT_EQ(r.motions, 2);  // the plunge, then the slot as one motion
  EXPECT_EQ(r.merged, 19);
  EXPECT_TRUE(r.alarms.empty());
  EXPECT_TRUE(r.errors.empty());
  const double removed = full - carver.simulation().stock().volume();
  const double expected = 2 * (pi * 9 + 20 * 6);  // 2 mm deep: hole and slot
  EXPECT_NEAR(removed, expected, 0.03 * expected);
  // The cycle time is the machine's: 210 ms of polls.
  EXPECT_NEAR(carver.simulation().snapshot(0).stats.cycle_time_s, 0.21, 1e-9);
}

// A tool too thin for any contact to pass the tolerance (check refuses it): the machine
// moves it anyway, so the shadow carves it and says so once, not at every motion.
TEST(ShadowCarver, AThinToolIsCarvedAndReportedOnce) {
  protocol::Job job = cellJob();
  job.tools[0].diameter = job.tools[0].shank_diameter = 0.2;  // density 5: tolerance 0.1
  const kin::Kinematics kin(*job.machine);
  ShadowCarver carver(job, kin, nullptr);
  const double full = carver.simulation().stock().volume();
  std::vector<PollSample> batch{at(10, 10, 5, 0), at(10, 10, -2, 10)};
  for (int i = 1; i <= 5; ++i) batch.push_back(at(10 + i, 10 + (i % 2), -2, 10 + 10 * i));
  const CarveResult r = carver.carve(batch);
  EXPECT_EQ(r.motions, 6);  // a zigzag: no two moves on one line
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors[0].find("tool 1's cutter"), std::string::npos) << r.errors[0];
  EXPECT_GT(full - carver.simulation().stock().volume(), 0.0);  // carved all the same
  const std::vector<PollSample> more{at(10, 10, 5, 100), at(12, 10, 5, 110)};
  EXPECT_TRUE(carver.carve(more).errors.empty());
}

TEST(ShadowCarver, StandingStillAndResyncCutNothing) {
  const protocol::Job job = cellJob();
  const kin::Kinematics kin(*job.machine);
  ShadowCarver carver(job, kin, nullptr);
  const double full = carver.simulation().stock().volume();
  CarveResult r =
      carver.carve(std::vector<PollSample>{at(10, 10, 5, 0), at(10, 10, 5, 1), at(10, 10, 5, 2)});
  EXPECT_EQ(r.motions, 0);
  // After a resync the machine is somewhere else: no motion is invented into it.
  PollSample jump = at(30, 30, -3, 500);
  jump.resync = true;
  r = carver.carve(std::vector<PollSample>{jump});
  EXPECT_EQ(r.motions, 0);
  EXPECT_DOUBLE_EQ(carver.simulation().stock().volume(), full);
  // From there on it cuts again: up and out of the stock through uncut material.
  r = carver.carve(std::vector<PollSample>{at(30, 30, 5, 520)});
  EXPECT_EQ(r.motions, 1);
  EXPECT_NEAR(full - carver.simulation().stock().volume(), pi * 9 * 3, 0.03 * pi * 27);
}

TEST(ShadowCarver, ACornerIsTwoMotionsAndSeparateBatchesAreNotMerged) {
  const protocol::Job job = cellJob();
  const kin::Kinematics kin(*job.machine);
  ShadowCarver carver(job, kin, nullptr);
  CarveResult r = carver.carve(std::vector<PollSample>{at(5, 5, -1, 0), at(10, 5, -1, 10),
                                                       at(15, 5, -1, 20), at(15, 10, -1, 30)});
  EXPECT_EQ(r.motions, 2);
  EXPECT_EQ(r.merged, 1);
  r = carver.carve(std::vector<PollSample>{at(15, 15, -1, 40)});
  EXPECT_EQ(r.motions, 1);
  EXPECT_EQ(r.merged, 0);
}

TEST(ShadowCarver, WithoutTheProgramEveryMoveIsAFeedAndSpindleOffIsAnAlarm) {
  const protocol::Job job = cellJob();
  const kin::Kinematics kin(*job.machine);
  ShadowCarver carver(job, kin, nullptr);
  CarveResult r = carver.carve(
      std::vector<PollSample>{at(10, 10, 5, 0, 6), at(10, 10, -1, 5, 7), at(10, 10, 5, 8, 7)});
  EXPECT_TRUE(r.alarms.empty());  // fast, but nothing says it is a rapid
  r = carver.carve(
      std::vector<PollSample>{at(20, 20, 5, 10, 8, false), at(20, 20, -1, 20, 9, false)});
  ASSERT_EQ(r.alarms.size(), 1u);
  EXPECT_EQ(r.alarms[0].type, check::CollisionType::kSpindleOffCut);
  EXPECT_EQ(r.alarms[0].line, 9);
  EXPECT_NEAR(r.alarms[0].depth, 1.0, 0.2);
  EXPECT_NEAR(r.alarms[0].position.z, 0.0, 0.15);
}

TEST(ShadowCarver, TheProgramSaysWhichMovesAreRapids) {
  const protocol::Job job = rapidIntoStockJob();
  const kin::Kinematics kin(*job.machine);
  const ProgramTrack track(job, kin);
  ShadowCarver carver(job, kin, &track);
  const CarveResult r = carver.carve(rapidIntoStockSamples());
  ASSERT_EQ(r.alarms.size(), 1u);
  EXPECT_EQ(r.alarms[0].type, check::CollisionType::kRapidIntoStock);
  EXPECT_EQ(r.alarms[0].line, 6);
  EXPECT_EQ(r.alarms[0].block, "G0 Z-1");
  EXPECT_NEAR(r.alarms[0].depth, 1.0, 0.2);
  ASSERT_TRUE(carver.cursor());
  EXPECT_EQ(track.at(*carver.cursor()).motion.pos.line, 8);
}

TEST(ShadowCarver, AContactIsHeardBeforeItsDepthIsMeasuredAndTheDepthIsTheSame) {
  const protocol::Job job = rapidIntoStockJob();
  const kin::Kinematics kin(*job.machine);
  const ProgramTrack track(job, kin);
  const std::vector<PollSample> batch = rapidIntoStockSamples();
  ShadowCarver heard(job, kin, &track);
  std::vector<std::pair<check::Collision, std::size_t>> calls;
  heard.setAlarmListener(
      [&](const check::Collision& c, std::size_t episode) { calls.emplace_back(c, episode); });
  const CarveResult r = heard.carve(batch);
  ShadowCarver quiet(job, kin, &track);
  const CarveResult q = quiet.carve(batch);

  ASSERT_EQ(calls.size(), 1u);
  ASSERT_EQ(r.alarms.size(), 1u);
  const check::Collision& first = calls[0].first;
  EXPECT_EQ(calls[0].second, 0u);
  EXPECT_EQ(first.type, check::CollisionType::kRapidIntoStock);
  EXPECT_EQ(first.line, 6);
  EXPECT_EQ(first.block, "G0 Z-1");
  // Placed by a coarse bisection first: at or after the exact first contact,
  // within 1/16 of the step (the rapid is 3 mm long).
  EXPECT_GE(first.path_s, r.alarms[0].path_s);
  EXPECT_LE(glm::distance(first.position, r.alarms[0].position), 3.0 / 16 + 1e-9);
  // A first bound: over the contact tolerance, not over the measured depth.
  EXPECT_GT(first.depth, heard.simulation().contactTolerance());
  EXPECT_LE(first.depth, r.alarms[0].depth);
  // The listener changes when the alarm is known, not what it says.
  ASSERT_EQ(q.alarms.size(), 1u);
  EXPECT_EQ(r.alarms[0].depth, q.alarms[0].depth);
  EXPECT_EQ(r.alarms[0].position, q.alarms[0].position);
  EXPECT_EQ(r.alarms[0].joints, q.alarms[0].joints);
  EXPECT_EQ(r.alarms[0].path_s, q.alarms[0].path_s);
  EXPECT_EQ(heard.simulation().collisions().size(), quiet.simulation().collisions().size());
  EXPECT_EQ(heard.simulation().stock().volume(), quiet.simulation().stock().volume());
}

}  // namespace
}  // namespace mdhd::shadow

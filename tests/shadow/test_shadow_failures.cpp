// A shadow against controllers that fail in the ways a black-box test found:
// replies dribbled a byte at a time, peers that never answer (stop and DELETE
// must not wait for them), a poll thread stuck (the watchdog), a refused
// feed-hold write, a tool the job does not define, a controller that never
// answers (the reason, not the backoff), a GET during a long carve, and a
// looping program's endless alarms.
#include <condition_variable>
#include <cstring>
#include <mutex>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "daemon/shadow_registry.h"
#include "tests/modbus/modbus_test_peers.h"
#include "tests/shadow/shadow_fixture.h"

namespace mdhd::shadow {
namespace {

using namespace std::chrono_literals;
using namespace mdhd::shadow::testing;
using modbus_test::Bytes;
using modbus_test::RawPeer;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using Kind = protocol::ModbusError::Kind;

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<nlohmann::json> eventsOf(ShadowSession& s, const std::string& type) {
  std::vector<nlohmann::json> out;
  for (const ShadowEvent& e : s.events().since(0, 0ms))
    if (e.type == type) out.push_back(nlohmann::json::parse(e.data));
  return out;
}

// The state events once the last one says `state` (it is published just after
// the state changes).
std::vector<nlohmann::json> statesUntil(ShadowSession& s, const std::string& state) {
  const auto deadline = std::chrono::steady_clock::now() + 2s;
  for (;;) {
    std::vector<nlohmann::json> out = eventsOf(s, "state");
    if ((!out.empty() && out.back()["state"] == state) ||
        std::chrono::steady_clock::now() > deadline)
      return out;
    std::this_thread::sleep_for(1ms);
  }
}

// The cell's 3-axis default map on `port`.
ShadowSpec failuresSpec(int port, int timeout_ms, double poll_hz = 100) {
  ShadowSpec spec;
  spec.job = cellJob();
  spec.map = protocol::defaultModbusMap(*spec.job.machine);
  spec.map.port = port;
  spec.map.poll_hz = poll_hz;
  spec.map.timeout_ms = timeout_ms;
  return spec;
}

// A controller in-process: the samples of `poses` in turn (the last one again
// and again), a feed-hold write that does what `hold` says, and a read that
// blocks (until interrupted) once `block_after` samples were served.
class ScriptedSource : public protocol::RegisterSource {
 public:
  struct Script {
    std::vector<protocol::ModbusSample> poses;
    std::function<void()> hold = [] {};
    std::size_t block_after = SIZE_MAX;
  };
  explicit ScriptedSource(std::shared_ptr<Script> script) : script_(std::move(script)) {}

  protocol::ModbusSample read() override {
    if (served_ >= script_->block_after) {
      std::unique_lock lock(mutex_);
      woken_.wait(lock, [&] { return interrupted_; });
      throw protocol::ModbusError(Kind::kInterrupted, 0, "interrupted");
    }
    const auto& poses = script_->poses;
    return poses[std::min(served_++, poses.size() - 1)];
  }
  void writeFeedHold(bool) override { script_->hold(); }
  void interrupt() override {
    std::lock_guard lock(mutex_);
    interrupted_ = true;
    woken_.notify_all();
  }

 private:
  std::shared_ptr<Script> script_;
  std::size_t served_ = 0;
  std::mutex mutex_;
  std::condition_variable woken_;
  bool interrupted_ = false;
};

ShadowSession::SourceFactory scripted(std::shared_ptr<ScriptedSource::Script> script) {
  return [script](const protocol::ModbusMap&) { return std::make_unique<ScriptedSource>(script); };
}

protocol::ModbusSample pose(double x, double y, double z, int tool = 1, bool spindle = true,
                            std::int64_t line = 7) {
  protocol::ModbusSample s;
  s.joints[gcode::kX] = x;
  s.joints[gcode::kY] = y;
  s.joints[gcode::kZ] = z + 40.0;
  s.joint_mask = 0b111;
  s.tool = tool;
  s.spindle_on = spindle;
  s.line = line;
  return s;
}

// Defect 1: each byte well within the timeout, the whole reply far beyond it.
// The old client (libmodbus, a per-byte timeout) stayed live on the old pose.
TEST(ShadowFailures, DribbledReplyMakesTheShadowStale) {
  std::atomic<int> requests{0};
  RawPeer peer([&](int, const Bytes& q, int fd) {
    const Bytes reply = modbus_test::readReply(q, defaultMapRegisters(10, 5));
    if (requests++ < 5) {
      modbus_test::sendAll(fd, reply);
      return true;
    }
    const auto until = std::chrono::steady_clock::now() + 400ms;
    for (std::uint8_t b : reply) {  // 35 bytes, one every 30 ms
      if (std::chrono::steady_clock::now() > until) return false;
      modbus_test::sendAll(fd, {b});
      std::this_thread::sleep_for(30ms);
    }
    return true;
  });
  ShadowSession session("t", failuresSpec(peer.port(), 100, 50));
  session.start();
  ASSERT_TRUE(waitState(session, ShadowState::kLive, 5s));
  while (requests.load() < 6) std::this_thread::sleep_for(1ms);
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(waitState(session, ShadowState::kStale, 2s));
  EXPECT_LT(msSince(t0), 1000);  // 100 ms and the wake-up
  const nlohmann::json s = session.status();
  EXPECT_THAT(s["polls"]["last_error"].get<std::string>(), HasSubstr("timeout: modbus 127.0.0.1"));
  EXPECT_THAT(s["polls"]["last_error"].get<std::string>(),
              HasSubstr("no complete reply within 100 ms"));
  const auto t1 = std::chrono::steady_clock::now();
  session.stop();
  EXPECT_LT(msSince(t1), 1000);
}

// Defect 2: a peer that accepts and never answers, timeout_ms 60000. The old
// stop() joined the poll thread inside modbus_read_registers: 59 s.
TEST(ShadowFailures, StopDoesNotWaitForAPeerThatNeverAnswers) {
  RawPeer peer([](int, const Bytes&, int) { return true; });
  ShadowSession session("t", failuresSpec(peer.port(), 60000, 50));
  session.start();
  while (peer.connections() < 1) std::this_thread::sleep_for(2ms);
  std::this_thread::sleep_for(100ms);  // the request is sent, the read is blocked
  const auto t0 = std::chrono::steady_clock::now();
  session.stop();
  const double ms = msSince(t0);
  EXPECT_LT(ms, 500);  // about 1 ms; generous for a loaded machine
  EXPECT_EQ(session.state(), ShadowState::kStopped);
  EXPECT_EQ(session.status()["polls"]["failed"], 0);  // the interrupt is no failure
}

// SIGTERM of `mdhd serve` stops the registry: three blocked shadows at once.
TEST(ShadowFailures, StoppingEveryShadowDoesNotWaitForTheirPeers) {
  RawPeer peer([](int, const Bytes&, int) { return true; });
  ShadowRegistry registry(8, 4);
  for (int i = 0; i < 3; ++i) {
    ASSERT_NE(registry.add(std::make_unique<ShadowSession>("t" + std::to_string(i),
                                                           failuresSpec(peer.port(), 20000, 50))),
              nullptr);
  }
  std::this_thread::sleep_for(300ms);
  const auto t0 = std::chrono::steady_clock::now();
  registry.stopAll();
  EXPECT_LT(msSince(t0), 1000);  // the old code: 19 s
}

// The watchdog: a poll thread that gets no sample (here a source stuck in a
// read) makes a live shadow stale after a poll period plus timeout_ms.
TEST(ShadowFailures, WatchdogMakesTheShadowStaleWhenNoSampleComes) {
  auto script = std::make_shared<ScriptedSource::Script>();
  script->poses = {pose(10, 20, 5)};
  script->block_after = 10;
  ShadowSession session("t", failuresSpec(0, 100, 100), {}, scripted(script));
  session.start();
  ASSERT_TRUE(waitState(session, ShadowState::kLive, 5s));
  ASSERT_TRUE(waitState(session, ShadowState::kStale, 3s));
  const std::vector<nlohmann::json> states = statesUntil(session, "stale");
  ASSERT_FALSE(states.empty());
  ASSERT_EQ(states.back()["state"], "stale");
  EXPECT_THAT(states.back()["reason"].get<std::string>(),
              StartsWith("watchdog: no good sample for"));
  const auto t0 = std::chrono::steady_clock::now();
  session.stop();  // interrupts the stuck read
  EXPECT_LT(msSince(t0), 500);
}

// Defect 3: a refused feed-hold write was retried forever, silently.
TEST(ShadowFailures, RefusedFeedHoldWriteIsReported) {
  auto script = std::make_shared<ScriptedSource::Script>();
  // Into the stock with the spindle off: a spindle_off_cut alarm, then a hold.
  script->poses = {pose(10, 20, 5), pose(10, 20, -2, 1, false), pose(20, 20, -2, 1, false)};
  std::atomic<int> attempts{0};
  script->hold = [&attempts] {
    ++attempts;
    throw protocol::ModbusError(Kind::kException, 0,
                                "modbus 127.0.0.1:502: write coil 7: Illegal data value");
  };
  ShadowSpec spec = failuresSpec(0, 100, 100);
  spec.map.feed_hold = {7, true};
  ShadowSession session("t", spec, {}, scripted(script));
  session.start();
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (attempts.load() < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(2ms);
  const nlohmann::json s = session.status();
  session.stop();
  ASSERT_GE(attempts.load(), 3);  // retried at every poll
  ASSERT_FALSE(s["alarms"].empty());
  EXPECT_EQ(s["feed_hold"]["writes"], 0);
  EXPECT_GE(s["feed_hold"]["failures"].get<int>(), 3);
  EXPECT_EQ(s["feed_hold"]["pending"], true);
  EXPECT_THAT(s["feed_hold"]["error"].get<std::string>(),
              StartsWith("feed_hold: exception: modbus 127.0.0.1:502: write coil 7"));
  EXPECT_THAT(s["polls"]["last_error"].get<std::string>(), StartsWith("feed_hold: exception"));
  const std::vector<nlohmann::json> holds = eventsOf(session, "feed_hold");
  ASSERT_EQ(holds.size(), 1u);  // once per run of failures, not at every retry
  EXPECT_EQ(holds[0]["ok"], false);
  EXPECT_EQ(holds[0]["coil"], 7);
}

// Defect 4: a tool the job does not define cut and checked nothing, silently.
TEST(ShadowFailures, UnknownToolMakesTheShadowStaleNotBlind) {
  auto script = std::make_shared<ScriptedSource::Script>();
  script->poses = {pose(10, 20, 5, 99), pose(10, 20, -10, 99), pose(10, 20, -15, 99)};
  ShadowSession session("t", failuresSpec(0, 100, 100), {}, scripted(script));
  const double full = session.stockVolume();
  session.start();
  const auto deadline = std::chrono::steady_clock::now() + 3s;
  while (session.status()["polls"]["failed"].get<int>() < 5 &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(2ms);
  const nlohmann::json s = session.status();
  session.stop();
  EXPECT_EQ(s["state"], "stale");  // the controller answered: not "connecting"
  EXPECT_EQ(s["samples"], 0);
  EXPECT_THAT(s["polls"]["last_error"].get<std::string>(),
              StartsWith("unknown_tool: the machine holds tool 99, which the job does not define "
                         "(its tools: 1)"));
  EXPECT_DOUBLE_EQ(session.stockVolume(), full);  // nothing invented either
}

TEST(ShadowFailures, UnknownToolAfterLiveGoesStaleWithTheReason) {
  auto script = std::make_shared<ScriptedSource::Script>();
  for (int i = 0; i < 20; ++i) script->poses.push_back(pose(10, 20, 5));
  script->poses.push_back(pose(10, 20, -10, 99));
  ShadowSession session("t", failuresSpec(0, 100, 200), {}, scripted(script));
  session.start();
  ASSERT_TRUE(waitState(session, ShadowState::kLive, 3s));
  ASSERT_TRUE(waitState(session, ShadowState::kStale, 3s));
  const std::vector<nlohmann::json> states = statesUntil(session, "stale");
  session.stop();
  ASSERT_GE(states.size(), 3u);
  EXPECT_EQ(states[2]["state"], "stale");
  EXPECT_THAT(states[2]["reason"].get<std::string>(),
              StartsWith("unknown_tool: the machine holds tool 99"));
}

// Defect 5: last_error only ever said "backoff: reconnecting in N ms".
TEST(ShadowFailures, NeverConnectingShowsWhyNotTheBackoff) {
  ShadowSession session("t", failuresSpec(modbus_test::freePort(), 100, 50));
  session.start();
  std::this_thread::sleep_for(700ms);
  const nlohmann::json s = session.status();
  session.stop();
  EXPECT_EQ(s["state"], "connecting");
  EXPECT_THAT(s["polls"]["last_error"].get<std::string>(), StartsWith("connect: modbus 127.0.0.1"));
  EXPECT_THAT(s["polls"]["last_error"].get<std::string>(), HasSubstr("Connection refused"));
  // 50, 100, 200, 400 ms of backoff: about 5 attempts, the other polls waited.
  EXPECT_GE(s["polls"]["failed"].get<int>(), 2);
  EXPECT_LE(s["polls"]["failed"].get<int>(), 8);
  EXPECT_GE(s["polls"]["backoff"].get<int>(), 10);
}

// Defect 6: GET waited for the carve thread's whole batch (up to 9 s).
TEST(ShadowFailures, StatusDoesNotWaitForALongCarve) {
  auto script = std::make_shared<ScriptedSource::Script>();
  script->poses = {pose(10, 20, 5), pose(10, 20, -1), pose(20, 20, -1)};
  std::atomic<bool> carving{false};
  SessionOptions options;
  options.while_carving = [&carving] {
    if (carving.exchange(true)) return;
    std::this_thread::sleep_for(2s);  // the first batch stands for a long one
  };
  ShadowSession session("t", failuresSpec(0, 100, 100), options, scripted(script));
  session.start();
  while (!carving.load()) std::this_thread::sleep_for(1ms);
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json s = session.status();
  EXPECT_LT(msSince(t0), 500);  // the old code: the 2 s of the batch
  EXPECT_TRUE(s["report"].is_object());
  EXPECT_GE(s["report_age_ms"].get<double>(), 0.0);
  ASSERT_TRUE(session.waitIdle(10s));
  const nlohmann::json after = session.status();
  session.stop();
  // Once the carving is idle the snapshot is the stock's as cut.
  EXPECT_GT(after["report"]["stats"]["removed_volume_mm3"].get<double>(), 0.0);
}

// Defect 8: a looping program raised alarms without bound. Axis-limit
// excursions: each one is an episode, an alarm.
TEST(ShadowFailures, AlarmsAreCappedFirstAndLatestKept) {
  auto script = std::make_shared<ScriptedSource::Script>();
  const std::size_t excursions = kKeepFirstAlarms + kKeepLastAlarms + 50;
  // Out past X's limit of 400 and back, then a step in Y inside the limits: the
  // episode ends there (a corner each time: no samples merged).
  script->poses.push_back(pose(390, 0, 100));
  for (std::size_t i = 0; i < excursions; ++i) {
    const double y = 0.1 * static_cast<double>(i);
    script->poses.push_back(pose(410, y, 100));
    script->poses.push_back(pose(390, y, 100));
    script->poses.push_back(pose(390, y + 0.1, 100));
  }
  ShadowSession session("t", failuresSpec(0, 100, 1000), {}, scripted(script));
  session.start();
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (session.status()["samples"].get<std::size_t>() < script->poses.size() &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(10ms);
  ASSERT_TRUE(session.waitIdle(10s));
  const nlohmann::json s = session.status();
  session.stop();
  ASSERT_EQ(s["alarms"].size(), kKeepFirstAlarms + kKeepLastAlarms);
  EXPECT_EQ(s["alarms_dropped"], 50);
  EXPECT_EQ(s["alarms"][0]["id"], 0);
  EXPECT_EQ(s["alarms"][kKeepFirstAlarms - 1]["id"], kKeepFirstAlarms - 1);
  EXPECT_EQ(s["alarms"][kKeepFirstAlarms]["id"], kKeepFirstAlarms + 50);
  EXPECT_EQ(s["alarms"].back()["id"], excursions - 1);
  EXPECT_EQ(s["alarms"].back()["type"], "axis_limit");
}

}  // namespace
}  // namespace mdhd::shadow

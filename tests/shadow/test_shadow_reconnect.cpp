// A shadow whose controller goes away: the real `mdhd modbus-sim` killed mid-run
// and started again on the same port (stale, then live again, the stock kept and
// finished right), and a raw Modbus peer that answers with garbage, exception
// replies, short frames and NaN between good answers.
#include <csignal>
#include <cstring>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/modbus/modbus_test_peers.h"
#include "tests/shadow/shadow_fixture.h"
#include "tests/shadow/shadow_sim.h"

namespace mdhd::shadow {
namespace {

using namespace mdhd::shadow::testing;
using modbus_test::Bytes;
using modbus_test::RawPeer;
using modbus_test::SimProcess;

using std::numbers::pi;

std::vector<std::string> stateSequence(ShadowSession& s) {
  std::vector<std::string> out;
  for (const ShadowEvent& e : s.events().since(0, 0ms))
    if (e.type == "state") out.push_back(nlohmann::json::parse(e.data)["state"]);
  return out;
}

int lineOf(const ShadowSession& s) {
  const nlohmann::json line = s.status()["line"];
  return line.is_number() ? line.get<int>() : -1;
}

TEST(ShadowReconnect, SimulatorKilledAndRestartedMidRun) {
  const cli::LoadedJob loaded = cli::loadCheckedJobFile(examplePath("contour-3axis"));
  const double check_volume = cli::runCheckJob(loaded).stats.final_volume_mm3;
  const std::vector<std::string> args = {
      kBin,           "modbus-sim", examplePath("contour-3axis"), "--port", "0", "--speed", "10",
      "--exit-after", "60"};
  auto sim = std::make_unique<SimProcess>(args);
  const int port = listeningPort(*sim);
  ASSERT_GT(port, 0);
  ShadowSession session("t", exampleSpec(loaded, port));
  const FinalPose end = finalPose(session.spec());
  session.start();
  // Into the contour (line 9 is the first arc), then the controller dies.
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (lineOf(session) < 9 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(2ms);
  ASSERT_GE(lineOf(session), 9);
  sim->stop(SIGKILL, 5s);
  ASSERT_TRUE(waitState(session, ShadowState::kStale, 2s));
  ASSERT_TRUE(session.waitIdle(10s));  // what was polled before is cut
  const double volume_at_kill = session.stockVolume();
  std::this_thread::sleep_for(400ms);
  EXPECT_EQ(session.state(), ShadowState::kStale);
  EXPECT_DOUBLE_EQ(session.stockVolume(), volume_at_kill);  // kept, nothing invented

  // The controller comes back on the same port and runs the program from the start.
  std::vector<std::string> again = args;
  again[4] = std::to_string(port);
  sim = std::make_unique<SimProcess>(again);
  ASSERT_EQ(listeningPort(*sim), port);
  ASSERT_TRUE(waitFinished(session, end, 30s));
  EXPECT_NEAR(session.stockVolume(), check_volume, 0.01 * check_volume);
  EXPECT_TRUE(session.alarms().empty());
  EXPECT_THAT(stateSequence(session),
              ::testing::ElementsAre("connecting", "live", "stale", "live"));
  const ShadowCounters c = session.counters();
  EXPECT_GT(c.polls_failed, 0u);
  EXPECT_THAT(session.status()["polls"]["last_error"].get<std::string>(),
              ::testing::AnyOf(::testing::HasSubstr("connect"), ::testing::HasSubstr("lost"),
                               ::testing::HasSubstr("backoff")));
  session.stop();
}

TEST(ShadowReconnect, SurvivesGarbageExceptionsShortFramesAndNaN) {
  std::atomic<int> requests{0};
  constexpr int kRequests = 120;  // x advances 0.1 mm per good answer
  std::atomic<float> x{5.0f};
  RawPeer peer([&](int, const Bytes& q, int fd) {
    const int n = requests++;
    const float at = x.load();
    switch (n) {
      case 30:  // garbage: not a Modbus frame
        modbus_test::sendAll(fd, {0xde, 0xad, 0xbe, 0xef, 0x00, 0x01});
        return true;
      case 45: {  // exception reply: illegal data address
        modbus_test::sendAll(
            fd, {q[0], q[1], 0, 0, 0, 3, q[6], static_cast<std::uint8_t>(q[7] | 0x80), 2});
        return true;
      }
      case 60: {  // half a reply, then the peer hangs up
        Bytes r = modbus_test::readReply(q, defaultMapRegisters(at, -1));
        r.resize(r.size() / 2);
        modbus_test::sendAll(fd, r);
        return false;
      }
      case 75: {  // another transaction's reply
        Bytes r = modbus_test::readReply(q, defaultMapRegisters(at, -1));
        r[1] ^= 0x55;
        modbus_test::sendAll(fd, r);
        return true;
      }
      case 90: {  // NaN for X
        std::vector<std::uint16_t> regs = defaultMapRegisters(at, -1);
        regs[0] = 0x7FC0;
        regs[1] = 0;
        modbus_test::sendAll(fd, modbus_test::readReply(q, regs));
        return true;
      }
      default:
        if (n < kRequests) x = at + 0.1f;
        modbus_test::sendAll(fd, modbus_test::readReply(q, defaultMapRegisters(x.load(), -1)));
        return true;
    }
  });
  ShadowSpec spec;
  spec.job = cellJob();
  spec.map = protocol::defaultModbusMap(*spec.job.machine);
  spec.map.port = peer.port();
  spec.map.poll_hz = 200;
  spec.map.timeout_ms = 50;
  ShadowSession session("t", spec);
  const double full = session.stockVolume();
  session.start();
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (requests.load() < kRequests + 10 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(5ms);
  ASSERT_TRUE(session.waitIdle(5s));
  const nlohmann::json s = session.status();
  session.stop();
  EXPECT_EQ(s["state"], "live");
  EXPECT_GE(s["polls"]["failed"].get<int>(), 5);
  EXPECT_GE(peer.connections(), 3);  // garbage, the short frame and the wrong id reconnect
  EXPECT_NEAR(s["joints"]["X"].get<double>(), x.load(), 1e-6);
  const std::vector<std::string> states = stateSequence(session);
  EXPECT_GE(std::count(states.begin(), states.end(), "stale"), 4);
  EXPECT_EQ(states[states.size() - 2], "live");
  // Every good pose was cut: a 1 mm deep slot from x = 5 on, the gaps bridged.
  const double length = x.load() - 5.0;
  const double slot = length * 6 + pi * 9;
  EXPECT_GT(length, 10.0);
  EXPECT_NEAR(full - session.stockVolume(), slot, 0.03 * slot);
  EXPECT_TRUE(session.alarms().empty());
}

}  // namespace
}  // namespace mdhd::shadow

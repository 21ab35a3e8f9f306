// Feed hold against a controller that answers reads but never the coil write.
// Measured on the old code with `mdhd serve` and a raw peer: after the first
// write timed out the shadow tried the write again before every read, each try a
// timeout and a reconnect, so no read was ever made again: polls.ok stayed at 78
// for as long as the shadow ran, the shadow stale and blind while the machine
// (not held) went on cutting.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/modbus/modbus_test_peers.h"
#include "tests/shadow/shadow_fixture.h"

namespace mdhd::shadow {
namespace {

using namespace std::chrono_literals;
using namespace mdhd::shadow::testing;
using modbus_test::Bytes;
using modbus_test::RawPeer;
using ::testing::HasSubstr;

constexpr std::uint8_t kWriteCoil = 0x05;

nlohmann::json statusWhen(const ShadowSession& s,
                          const std::function<bool(const nlohmann::json&)>& ok,
                          std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  nlohmann::json j = s.status();
  while (!ok(j) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(5ms);
    j = s.status();
  }
  return j;
}

TEST(ShadowFeedHold, AWriteTheControllerIgnoresDoesNotStopThePolls) {
  std::atomic<int> reads{0}, writes{0};
  RawPeer peer([&](int, const Bytes& q, int fd) {
    if (q.size() > 7 && q[7] == kWriteCoil) {
      ++writes;
      return true;  // never answered
    }
    // Above the stock, then down into it with the spindle off: an alarm, a hold.
    std::vector<std::uint16_t> registers = defaultMapRegisters(10, reads++ >= 10 ? -2.0f : 5.0f);
    registers[7] = 0;  // spindle_on
    modbus_test::sendAll(fd, modbus_test::readReply(q, registers));
    return true;
  });
  ShadowSpec spec;
  spec.job = cellJob();
  spec.map = protocol::defaultModbusMap(*spec.job.machine);
  spec.map.port = peer.port();
  spec.map.poll_hz = 50;
  spec.map.timeout_ms = 100;
  spec.map.feed_hold = {3, true};
  ShadowSession session("t", spec);
  session.start();
  const nlohmann::json failed = statusWhen(
      session, [](const nlohmann::json& j) { return j["feed_hold"]["failures"] >= 1; }, 5s);
  ASSERT_GE(failed["feed_hold"]["failures"].get<int>(), 1);
  ASSERT_FALSE(failed["alarms"].empty());
  const int ok_then = failed["polls"]["ok"].get<int>();
  std::this_thread::sleep_for(1500ms);
  const nlohmann::json later = session.status();
  session.stop();
  // 75 polls in 1.5 s at 50 Hz, less the tries (each a 100 ms timeout and a
  // reconnect): the old code made none.
  EXPECT_GE(later["polls"]["ok"].get<int>() - ok_then, 25) << later["polls"].dump();
  // Still tried, with a backoff (50, 100, 200, 400, 800 ms): not at every poll.
  EXPECT_GE(writes.load(), 3);
  EXPECT_LE(writes.load(), 9);
  EXPECT_EQ(later["feed_hold"]["writes"], 0);
  EXPECT_EQ(later["feed_hold"]["pending"], true);
  EXPECT_THAT(later["feed_hold"]["error"].get<std::string>(),
              HasSubstr("feed_hold: timeout: modbus 127.0.0.1:" + std::to_string(peer.port()) +
                        ": write coil 3: no complete reply within 100 ms"));
}

}  // namespace
}  // namespace mdhd::shadow

// A shadow whose controller is named by a host name the resolver does not answer
// for. Measured on the old code with `mdhd serve` and a DNS server that drops
// queries (glibc: 5 s x 2 tries): the shadow stayed `connecting` with no
// last_error for 10 s, a live one lost its connection and then showed nothing
// new, and DELETE took 4.4-6.8 s (the poll thread was in getaddrinfo).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/modbus/modbus_test_peers.h"
#include "tests/modbus/resolver_gate.h"
#include "tests/shadow/shadow_fixture.h"

namespace mdhd::shadow {
namespace {

using namespace std::chrono_literals;
using namespace mdhd::shadow::testing;
using modbus_test::Bytes;
using modbus_test::RawPeer;
using modbus_test::ResolverGate;
using ::testing::HasSubstr;

ShadowSpec namedSpec(int port) {
  ShadowSpec spec;
  spec.job = cellJob();
  spec.map = protocol::defaultModbusMap(*spec.job.machine);
  spec.map.host = "plc.test";
  spec.map.port = port;
  spec.map.poll_hz = 50;
  spec.map.timeout_ms = 100;
  return spec;
}

ShadowSession::SourceFactory resolvingThrough(std::shared_ptr<ResolverGate> gate) {
  return [gate](const protocol::ModbusMap& map) {
    return std::make_unique<protocol::ModbusTcpClient>(map, protocol::BackoffPolicy{},
                                                       protocol::ModbusTcpClient::Clock{},
                                                       modbus_test::gatedResolver(gate));
  };
}

std::string lastErrorOf(const ShadowSession& s) {
  const nlohmann::json e = s.status()["polls"]["last_error"];
  return e.is_string() ? e.get<std::string>() : "";
}

double msAfter(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

TEST(ShadowResolve, UnresolvedHostSaysSoAndDeleteIsImmediate) {
  auto gate = std::make_shared<ResolverGate>();
  ShadowSession session("t", namedSpec(502), {}, resolvingThrough(gate));
  session.start();
  const auto deadline = std::chrono::steady_clock::now() + 3s;
  while (lastErrorOf(session).empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(5ms);
  EXPECT_EQ(lastErrorOf(session),
            "timeout: modbus plc.test:502: connect: the host name plc.test did not resolve "
            "within 100 ms (the lookup goes on; a later attempt takes its answer) (next attempt "
            "in 50 ms)");
  EXPECT_EQ(session.state(), ShadowState::kConnecting);
  EXPECT_EQ(gate->calls.load(), 1);  // one lookup, however many attempts
  const auto t0 = std::chrono::steady_clock::now();
  session.stop();
  EXPECT_LT(msAfter(t0), 500);  // the old code: until the resolver gave up (5 s)
  gate->release();
}

TEST(ShadowResolve, LiveShadowWhoseReconnectHangsInTheResolverGoesStaleAndStops) {
  std::atomic<int> requests{0};
  RawPeer peer([&](int connection, const Bytes& q, int fd) {
    if (connection == 0 && requests++ >= 10) return false;  // the controller drops us
    modbus_test::sendAll(fd, modbus_test::readReply(q, defaultMapRegisters(10, 5)));
    return true;
  });
  auto gate = std::make_shared<ResolverGate>();
  gate->free_calls = 1;  // the first lookup answers, the one after the drop hangs
  ShadowSession session("t", namedSpec(peer.port()), {}, resolvingThrough(gate));
  session.start();
  ASSERT_TRUE(waitState(session, ShadowState::kLive, 5s));
  ASSERT_TRUE(waitState(session, ShadowState::kStale, 3s));
  const auto deadline = std::chrono::steady_clock::now() + 3s;
  while (lastErrorOf(session).find("did not resolve") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(5ms);
  EXPECT_THAT(lastErrorOf(session), HasSubstr("the host name plc.test did not resolve within"));
  EXPECT_GE(session.status()["polls"]["failed"].get<int>(), 2);  // the drop, then the resolver
  const auto t0 = std::chrono::steady_clock::now();
  session.stop();
  EXPECT_LT(msAfter(t0), 500);
  EXPECT_EQ(session.state(), ShadowState::kStopped);
  // Released: the same lookup answers a client that no longer exists; nothing breaks.
  gate->release();
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(gate->calls.load(), 2);
}

}  // namespace
}  // namespace mdhd::shadow

// Resolving the controller's host name: bounded by timeout_ms and by interrupt(),
// however long the system's resolver takes (the old client called getaddrinfo on
// the polling thread: a resolver that did not answer held a poll, and the stop of
// its shadow, for the resolver's own timeout: 10 s here with one silent server).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <thread>

#include "protocol/modbus_client.h"
#include "tests/modbus/modbus_test_peers.h"
#include "tests/modbus/resolver_gate.h"

namespace mdhd::protocol {
namespace {

using namespace std::chrono_literals;
using modbus_test::Bytes;
using modbus_test::RawPeer;
using modbus_test::ResolverGate;
using ::testing::HasSubstr;

ModbusMap resolveMap(const std::string& host, int port, int timeout_ms) {
  ModbusMap map;
  map.host = host;
  map.port = port;
  map.timeout_ms = timeout_ms;
  map.joints = {{"X", gcode::kX, {0, RegisterType::kFloat32}}};
  return map;
}

RawPeer answersOnePointFive() {
  return RawPeer([](int, const Bytes& q, int fd) {
    modbus_test::sendAll(fd, modbus_test::readReply(q, {0x3FC0, 0x0000}));
    return true;
  });
}

double msFrom(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

TEST(ModbusResolve, ASilentResolverCostsAPollTimeoutMsAndTheLateAnswerIsUsed) {
  RawPeer peer = answersOnePointFive();
  auto gate = std::make_shared<ResolverGate>();
  ModbusTcpClient client(resolveMap("plc.test", peer.port(), 150), {}, {},
                         modbus_test::gatedResolver(gate));
  auto t0 = std::chrono::steady_clock::now();
  try {
    client.read();
    ADD_FAILURE() << "read without an address";
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), ModbusError::Kind::kTimeout);
    EXPECT_THAT(e.what(), HasSubstr("modbus plc.test:" + std::to_string(peer.port()) +
                                    ": connect: the host name plc.test did not resolve within "
                                    "150 ms"));
  }
  const double ms = msFrom(t0);
  EXPECT_GE(ms, 140);
  EXPECT_LT(ms, 1000);  // the old client: until the resolver answered (5 s here)
  // The next attempt, after the backoff, waits for the same lookup: no second one.
  std::this_thread::sleep_until(client.nextAttempt() + 1ms);
  t0 = std::chrono::steady_clock::now();
  EXPECT_THROW(client.read(), ModbusError);
  EXPECT_LT(msFrom(t0), 1000);
  EXPECT_EQ(gate->calls.load(), 1);
  gate->release();
  std::this_thread::sleep_until(client.nextAttempt() + 1ms);
  EXPECT_EQ(client.read().joints[gcode::kX], 1.5);
  EXPECT_EQ(gate->calls.load(), 1);
  EXPECT_EQ(client.connects(), 1u);
}

TEST(ModbusResolve, InterruptEndsAPollWaitingForTheResolver) {
  auto gate = std::make_shared<ResolverGate>();
  ModbusTcpClient client(resolveMap("plc.test", 502, 60000), {}, {},
                         modbus_test::gatedResolver(gate));
  std::thread stopper([&] {
    while (gate->calls.load() == 0) std::this_thread::sleep_for(1ms);
    std::this_thread::sleep_for(50ms);
    client.interrupt();
  });
  const auto t0 = std::chrono::steady_clock::now();
  try {
    client.read();
    ADD_FAILURE() << "read without an address";
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), ModbusError::Kind::kInterrupted);
  }
  stopper.join();
  EXPECT_LT(msFrom(t0), 1000);  // 50 ms; the old client: 5 s (the resolver's give-up)
  gate->release();
}

TEST(ModbusResolve, ANameThatDoesNotResolveSaysWhy) {
  ModbusTcpClient client(resolveMap("plc.test", 502, 150), {}, {},
                         [](const std::string& host, int) -> std::vector<Endpoint> {
                           throw std::runtime_error(host + ": Name or service not known");
                         });
  try {
    client.read();
    ADD_FAILURE() << "read without an address";
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), ModbusError::Kind::kConnect);
    EXPECT_THAT(e.what(), HasSubstr("connect: cannot resolve the host: plc.test: Name or "
                                    "service not known (next attempt in 50 ms)"));
  }
}

TEST(ModbusResolve, AnAddressNeverAsksTheResolverAndLocalhostResolves) {
  RawPeer peer = answersOnePointFive();
  auto gate = std::make_shared<ResolverGate>();
  {
    ModbusTcpClient numeric(resolveMap("127.0.0.1", peer.port(), 150), {}, {},
                            modbus_test::gatedResolver(gate));
    EXPECT_EQ(numeric.read().joints[gcode::kX], 1.5);
    EXPECT_EQ(gate->calls.load(), 0);
  }  // closed: the peer serves one connection at a time
  // The real resolver (getaddrinfo) for a name of /etc/hosts.
  ModbusTcpClient named(resolveMap("localhost", peer.port(), 1000));
  EXPECT_EQ(named.read().joints[gcode::kX], 1.5);
  gate->release();
}

}  // namespace
}  // namespace mdhd::protocol

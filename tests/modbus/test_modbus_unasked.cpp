// A peer that sends bytes no request asked for: after a good reply, or between
// polls. Measured on the old client with a raw peer through `mdhd serve`: the
// shadow's last_error said "the reply's transaction id is 0x0090, not 0x0091
// (another request's reply)", which sends the user looking for a second client.
// Now the poll says what happened and the client recovers as after any garbage.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <thread>

#include "protocol/modbus_client.h"
#include "tests/modbus/modbus_test_peers.h"

namespace mdhd::protocol {
namespace {

using namespace std::chrono_literals;
using modbus_test::Bytes;
using modbus_test::RawPeer;
using ::testing::HasSubstr;

ModbusMap unaskedMap(int port) {
  ModbusMap map;
  map.host = "127.0.0.1";
  map.port = port;
  map.timeout_ms = 150;
  map.joints = {{"X", gcode::kX, {0, RegisterType::kFloat32}}};
  return map;
}

std::string failureOf(ModbusTcpClient& client, ModbusError::Kind& kind) {
  try {
    client.read();
  } catch (const ModbusError& e) {
    kind = e.kind();
    return e.what();
  }
  return "";
}

TEST(ModbusUnasked, BytesAfterAReplyAreNamedAndTheClientRecovers) {
  RawPeer peer([](int connection, const Bytes& q, int fd) {
    Bytes reply = modbus_test::readReply(q, {0x3FC0, 0x0000});
    // The first connection's first reply carries 9 bytes more: a copy of its header.
    if (connection == 0) reply.insert(reply.end(), reply.begin(), reply.begin() + 9);
    modbus_test::sendAll(fd, reply);
    return true;
  });
  ModbusTcpClient client(unaskedMap(peer.port()));
  EXPECT_EQ(client.read().joints[gcode::kX], 1.5);
  std::this_thread::sleep_for(20ms);  // the extra bytes are there before the next request
  ModbusError::Kind kind = ModbusError::Kind::kBackoff;
  const std::string message = failureOf(client, kind);
  EXPECT_EQ(kind, ModbusError::Kind::kMalformed);
  EXPECT_THAT(message, HasSubstr("read holding registers 0..1: the peer sent bytes no request "
                                 "asked for (0x00 0x01 0x00 0x00 0x00 0x07 0x01 0x03 ...) before "
                                 "this request"));
  std::this_thread::sleep_until(client.nextAttempt() + 1ms);
  EXPECT_EQ(client.read().joints[gcode::kX], 1.5);
  EXPECT_EQ(client.connects(), 2u);
}

TEST(ModbusUnasked, APeerThatClosedBetweenPollsIsALostConnectionBeforeTheRequest) {
  RawPeer peer([](int connection, const Bytes& q, int fd) {
    modbus_test::sendAll(fd, modbus_test::readReply(q, {0x3FC0, 0x0000}));
    return connection > 0;
  });
  ModbusTcpClient client(unaskedMap(peer.port()));
  EXPECT_EQ(client.read().joints[gcode::kX], 1.5);
  std::this_thread::sleep_for(30ms);
  ModbusError::Kind kind = ModbusError::Kind::kBackoff;
  EXPECT_THAT(failureOf(client, kind), HasSubstr("the peer closed the connection"));
  EXPECT_EQ(kind, ModbusError::Kind::kConnectionLost);
}

}  // namespace
}  // namespace mdhd::protocol

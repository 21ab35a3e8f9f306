// The libmodbus client against peers that misbehave (a raw TCP server answering
// garbage, short frames, exceptions, or closing mid-frame), a dead port (backoff),
// and pymodbus, a Modbus server no one here wrote, for every float word order.
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "protocol/modbus_client.h"
#include "tests/modbus/modbus_test_peers.h"

extern char** environ;

namespace mdhd::protocol {
namespace {

using namespace std::chrono_literals;
using Kind = ModbusError::Kind;
using modbus_test::Bytes;
using modbus_test::RawPeer;

constexpr int kTimeoutMs = 150;

ModbusMap mapFor(int port) {
  ModbusMap map;
  map.host = "127.0.0.1";
  map.port = port;
  map.timeout_ms = kTimeoutMs;
  map.joints = {{"X", gcode::kX, {0, RegisterType::kFloat32}}};
  map.line = RegisterField{2, RegisterType::kUint32};
  return map;
}

// 1.5 in X, line 7
const std::vector<std::uint16_t> kGoodRegisters = {0x3FC0, 0x0000, 0x0000, 0x0007};

struct Outcome {
  Kind kind;
  std::string message;
  double ms;
};

Outcome failedRead(ModbusTcpClient& client) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    client.read();
  } catch (const ModbusError& e) {
    return {
        e.kind(), e.what(),
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()};
  }
  ADD_FAILURE() << "the read succeeded";
  return {Kind::kBackoff, "", 0.0};
}

// A peer whose first connection gets `bad` and later ones a good answer.
RawPeer badThenGood(std::function<bool(const Bytes&, int)> bad) {
  return RawPeer([bad](int connection, const Bytes& req, int fd) {
    if (connection == 0) return bad(req, fd);
    modbus_test::sendAll(fd, modbus_test::readReply(req, kGoodRegisters));
    return true;
  });
}

// The client recovers: inside the backoff it says so, after it reads again.
void expectRecovery(ModbusTcpClient& client) {
  EXPECT_EQ(failedRead(client).kind, Kind::kBackoff);
  std::this_thread::sleep_until(client.nextAttempt() + 1ms);
  const ModbusSample s = client.read();
  EXPECT_EQ(s.joints[gcode::kX], 1.5);
  EXPECT_EQ(s.line, 7);
  EXPECT_EQ(client.connects(), 2u);
}

TEST(ModbusClient, ReadsAWellFormedPeer) {
  RawPeer peer([](int, const Bytes& req, int fd) {
    EXPECT_EQ(req.size(), 12u);
    EXPECT_EQ(req[7], 3);   // read holding registers
    EXPECT_EQ(req[9], 0);   // from 0
    EXPECT_EQ(req[11], 4);  // 4 registers
    modbus_test::sendAll(fd, modbus_test::readReply(req, kGoodRegisters));
    return true;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  for (int i = 0; i < 3; ++i) {
    const ModbusSample s = client.read();
    EXPECT_EQ(s.joints[gcode::kX], 1.5);
    EXPECT_EQ(s.line, 7);
  }
  EXPECT_EQ(client.connects(), 1u);
}

TEST(ModbusClient, GarbageIsMalformedAndTheClientReconnects) {
  RawPeer peer = badThenGood([](const Bytes&, int fd) {
    modbus_test::sendAll(fd, Bytes{'t', 'h', 'i', 's', ' ', 'i', 's', ' ', 'n', 'o', 't', '!'});
    return true;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kMalformed) << o.message;
  EXPECT_LT(o.ms, kTimeoutMs + 100);
  EXPECT_THAT(o.message, ::testing::HasSubstr("next attempt in 50 ms"));
  expectRecovery(client);
}

TEST(ModbusClient, WrongByteCountIsMalformed) {
  RawPeer peer = badThenGood([](const Bytes& req, int fd) {
    Bytes reply = modbus_test::readReply(req, {1, 2});  // 2 registers where 4 were asked
    modbus_test::sendAll(fd, reply);
    return true;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kMalformed) << o.message;
  expectRecovery(client);
}

TEST(ModbusClient, ShortFrameTimesOutWithinTheTimeout) {
  RawPeer peer = badThenGood([](const Bytes& req, int fd) {
    Bytes reply = modbus_test::readReply(req, kGoodRegisters);
    reply.resize(11);  // header and a register and a half, then nothing
    modbus_test::sendAll(fd, reply);
    return true;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kTimeout) << o.message;
  EXPECT_GE(o.ms, kTimeoutMs * 0.9);
  EXPECT_LT(o.ms, 2 * kTimeoutMs + 100);
  expectRecovery(client);
}

TEST(ModbusClient, SilentPeerTimesOut) {
  RawPeer peer = badThenGood([](const Bytes&, int) { return true; });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kTimeout) << o.message;
  EXPECT_LT(o.ms, kTimeoutMs + 100);
  expectRecovery(client);  // the late answer of the old connection cannot be taken
}

TEST(ModbusClient, PeerClosingMidFrameIsALostConnection) {
  RawPeer peer = badThenGood([](const Bytes& req, int fd) {
    Bytes reply = modbus_test::readReply(req, kGoodRegisters);
    reply.resize(5);
    modbus_test::sendAll(fd, reply);
    return false;  // close
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kConnectionLost) << o.message;
  EXPECT_LT(o.ms, kTimeoutMs + 100);
  expectRecovery(client);
}

TEST(ModbusClient, PeerVanishingBetweenPollsRaisesNoSigpipe) {
  RawPeer peer([](int connection, const Bytes& req, int fd) {
    modbus_test::sendAll(fd, modbus_test::readReply(req, kGoodRegisters));
    return connection > 0;  // the first connection closes after one answer
  });
  ModbusTcpClient client(mapFor(peer.port()));
  EXPECT_EQ(client.read().line, 7);
  std::this_thread::sleep_for(30ms);
  // Writing to the closed socket must not kill the process (SIGPIPE): an error.
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kConnectionLost) << o.message;
  expectRecovery(client);
}

TEST(ModbusClient, ExceptionReplyKeepsTheConnection) {
  RawPeer peer([](int, const Bytes& req, int fd) {
    modbus_test::sendAll(fd, Bytes{req[0], req[1], 0, 0, 0, 3, req[6], 0x83, 0x02});
    return true;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kException);
  EXPECT_THAT(o.message, ::testing::HasSubstr("read holding registers 0..3: Illegal data address"));
  EXPECT_TRUE(client.connected());
  EXPECT_EQ(failedRead(client).kind, Kind::kException);  // no backoff: still in step
  EXPECT_EQ(client.connects(), 1u);
}

TEST(ModbusClient, NanFromThePeerIsABadValueNotAPose) {
  RawPeer peer([](int, const Bytes& req, int fd) {
    modbus_test::sendAll(fd, modbus_test::readReply(req, {0x7FC0, 0x0000, 0, 1}));
    return true;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kBadValue);
  EXPECT_THAT(o.message, ::testing::HasSubstr("joints.X: the controller sent NaN"));
  EXPECT_TRUE(client.connected());
}

TEST(ModbusClient, BackoffDoublesToTwoSecondsAndResets) {
  auto now = std::chrono::steady_clock::time_point{} + 1h;
  ModbusTcpClient client(mapFor(modbus_test::freePort()), {}, [&now] { return now; });
  const long expected[] = {50, 100, 200, 400, 800, 1600, 2000, 2000};
  for (long wait : expected) {
    const Outcome refused = failedRead(client);
    EXPECT_EQ(refused.kind, Kind::kConnect) << refused.message;
    EXPECT_EQ(client.lastWait().count(), wait);
    EXPECT_EQ(client.nextAttempt(), now + std::chrono::milliseconds(wait));
    now += std::chrono::milliseconds(wait - 1);
    EXPECT_EQ(failedRead(client).kind, Kind::kBackoff);  // 1 ms early
    now += 1ms;
  }
  EXPECT_EQ(client.connects(), 0u);
}

TEST(ModbusClient, WritesTheFeedHoldCoil) {
  std::vector<Bytes> requests;
  RawPeer peer([&requests](int, const Bytes& req, int fd) {
    requests.push_back(req);
    modbus_test::sendAll(fd, req);  // a write-single-coil reply echoes the request
    return true;
  });
  ModbusMap map = mapFor(peer.port());
  map.feed_hold = {5, true};
  ModbusTcpClient client(map);
  client.writeFeedHold(true);
  client.writeFeedHold(false);
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[0], (Bytes{requests[0][0], requests[0][1], 0, 0, 0, 6, 1, 5, 0, 5, 0xFF, 0}));
  EXPECT_EQ(requests[1][10], 0x00);
}

// A reply sent a byte at a time, each byte well within the timeout: the whole
// exchange has one deadline, so the dribble is a timeout, not a stale pose.
TEST(ModbusClient, ReplyDribbledByteByByteTimesOutAtTheDeadline) {
  RawPeer peer = badThenGood([](const Bytes& req, int fd) {
    const Bytes reply = modbus_test::readReply(req, kGoodRegisters);
    // 15 bytes, one every 30 ms: 450 ms in all; the peer gives up (and serves the
    // next connection) once the client must have.
    const auto until =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(kTimeoutMs + 30);
    for (std::uint8_t b : reply) {
      if (std::chrono::steady_clock::now() > until) break;
      modbus_test::sendAll(fd, {b});
      std::this_thread::sleep_for(std::chrono::milliseconds(kTimeoutMs / 5));
    }
    return false;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kTimeout) << o.message;
  EXPECT_GE(o.ms, kTimeoutMs * 0.9);
  EXPECT_LT(o.ms, kTimeoutMs + 300);  // old client: 15 bytes x 30 ms, a byte timeout each
  EXPECT_THAT(o.message, ::testing::HasSubstr("no complete reply within 150 ms"));
  expectRecovery(client);
}

// interrupt() from another thread ends a read blocked on a peer that never
// answers (timeout 60 s) at once, and every later call.
TEST(ModbusClient, InterruptEndsABlockedReadAtOnce) {
  RawPeer peer([](int, const Bytes&, int) { return true; });  // accepts, never answers
  ModbusMap map = mapFor(peer.port());
  map.timeout_ms = 60000;
  ModbusTcpClient client(map);
  std::thread stopper([&client] {
    std::this_thread::sleep_for(100ms);
    client.interrupt();
  });
  const Outcome o = failedRead(client);
  stopper.join();
  EXPECT_EQ(o.kind, Kind::kInterrupted) << o.message;
  EXPECT_LT(o.ms, 1500);
  EXPECT_EQ(failedRead(client).kind, Kind::kInterrupted);
  EXPECT_FALSE(client.connected());
}

// libmodbus 3.1.6 took these replies: each must fail the poll as malformed.
void expectMalformed(std::function<Bytes(const Bytes& req)> reply, const char* says) {
  RawPeer peer = badThenGood([reply](const Bytes& req, int fd) {
    modbus_test::sendAll(fd, reply(req));
    return true;
  });
  ModbusTcpClient client(mapFor(peer.port()));
  const Outcome o = failedRead(client);
  EXPECT_EQ(o.kind, Kind::kMalformed) << o.message;
  EXPECT_THAT(o.message, ::testing::HasSubstr(says));
  EXPECT_LT(o.ms, kTimeoutMs);  // told at once, not a timeout
  expectRecovery(client);
}

TEST(ModbusClient, ReplyFromAnotherUnitIsMalformed) {
  expectMalformed(
      [](const Bytes& req) {
        Bytes r = modbus_test::readReply(req, kGoodRegisters);
        r[6] = static_cast<std::uint8_t>(r[6] + 1);
        return r;
      },
      "unit id 2, not 1");
}

TEST(ModbusClient, ReplyWithAnotherProtocolIdIsMalformed) {
  expectMalformed(
      [](const Bytes& req) {
        Bytes r = modbus_test::readReply(req, kGoodRegisters);
        r[3] = 7;
        return r;
      },
      "protocol id is 7");
}

TEST(ModbusClient, MbapLengthThatDoesNotMatchIsMalformed) {
  // Two bytes more than the byte count says, the MBAP length counting them.
  expectMalformed(
      [](const Bytes& req) {
        Bytes r = modbus_test::readReply(req, kGoodRegisters);
        r[5] = static_cast<std::uint8_t>(r[5] + 2);
        r.insert(r.end(), {0, 0});
        return r;
      },
      "PDU bytes");
  expectMalformed(
      [](const Bytes& req) {
        Bytes r = modbus_test::readReply(req, kGoodRegisters);
        r[4] = 0xFF;
        r[5] = 0xFF;
        return r;
      },
      "MBAP length is 65535");
  expectMalformed(
      [](const Bytes& req) {
        Bytes r = modbus_test::readReply(req, kGoodRegisters);
        r[5] = 0;
        return r;
      },
      "MBAP length is 0");
}

TEST(ModbusClient, RefusedCoilWriteIsAnException) {
  RawPeer peer([](int, const Bytes& req, int fd) {
    modbus_test::sendAll(fd, Bytes{req[0], req[1], 0, 0, 0, 3, req[6], 0x85, 0x04});
    return true;
  });
  ModbusMap map = mapFor(peer.port());
  map.feed_hold = {7, true};
  ModbusTcpClient client(map);
  try {
    client.writeFeedHold(true);
    ADD_FAILURE() << "the write succeeded";
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), Kind::kException);
    EXPECT_THAT(e.what(), ::testing::HasSubstr("write coil 7"));
  }
}

TEST(ModbusClient, CoilWriteEchoingAnotherValueFails) {
  RawPeer peer([](int, const Bytes& req, int fd) {
    Bytes r = req;
    r[10] = 0;  // echoes "off" where "on" was written
    modbus_test::sendAll(fd, r);
    return true;
  });
  ModbusMap map = mapFor(peer.port());
  map.feed_hold = {7, true};
  ModbusTcpClient client(map);
  try {
    client.writeFeedHold(true);
    ADD_FAILURE() << "the write succeeded";
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), Kind::kMalformed);
    EXPECT_THAT(e.what(),
                ::testing::HasSubstr("echoes coil 7 value 0x0000, not coil 7 value 0xff00"));
  }
}

// --- pymodbus ---

// Serves, for each pymodbus (byteorder, wordorder) pair i, at 10*i: float32 -123.25,
// int32 -123456, uint32 3000000000, int16 -2 (the last with byteorder Big only:
// pymodbus also swaps the bytes of 16-bit values under byteorder Little).
const char* kPymodbusServer = R"(
import logging
import sys
logging.disable(logging.CRITICAL)
from pymodbus.server import StartTcpServer
from pymodbus.datastore import ModbusSequentialDataBlock, ModbusSlaveContext, ModbusServerContext
from pymodbus.payload import BinaryPayloadBuilder
from pymodbus.constants import Endian
regs = [0] * 40
orders = [(Endian.Big, Endian.Big), (Endian.Little, Endian.Big),
          (Endian.Big, Endian.Little), (Endian.Little, Endian.Little)]
for i, (byteorder, wordorder) in enumerate(orders):
    b = BinaryPayloadBuilder(byteorder=byteorder, wordorder=wordorder)
    b.add_32bit_float(-123.25)
    b.add_32bit_int(-123456)
    b.add_32bit_uint(3000000000)
    b.add_16bit_int(-2)
    regs[10 * i:10 * i + 7] = b.to_registers()
store = ModbusSlaveContext(hr=ModbusSequentialDataBlock(0, regs), zero_mode=True)
StartTcpServer(context=ModbusServerContext(slaves=store, single=True),
               address=("127.0.0.1", int(sys.argv[1])))
)";

class PythonProcess {
 public:
  explicit PythonProcess(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, argv[0], nullptr, nullptr, argv.data(), environ) != 0) pid_ = -1;
  }
  ~PythonProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  bool started() const { return pid_ > 0; }

 private:
  pid_t pid_ = -1;
};

bool pythonHasPymodbus() {
  return std::system("/usr/bin/python3 -c 'import pymodbus.server' >/dev/null 2>&1") == 0;
}

TEST(ModbusClient, PymodbusPeerEveryWordOrder) {
  // scripts/install-deps.sh (run by the test command) installs the peer: without it
  // this test fails rather than skips, so a missing peer never passes unseen.
  ASSERT_TRUE(pythonHasPymodbus())
      << "/usr/bin/python3 cannot import pymodbus.server: run scripts/install-deps.sh "
         "(python3-pymodbus, python3-serial, python3-serial-asyncio)";
  const int port = modbus_test::freePort();
  PythonProcess server({"/usr/bin/python3", "-c", kPymodbusServer, std::to_string(port)});
  ASSERT_TRUE(server.started());
  const WordOrder orders[] = {WordOrder::kAbcd, WordOrder::kBadc, WordOrder::kCdab,
                              WordOrder::kDcba};
  for (int i = 0; i < 4; ++i) {
    ModbusMap map = mapFor(port);
    map.timeout_ms = 1000;
    map.line.reset();
    map.joints = {{"X", gcode::kX, {10 * i, RegisterType::kFloat32, orders[i]}},
                  {"Y", gcode::kY, {10 * i + 2, RegisterType::kInt32, orders[i]}},
                  {"Z", gcode::kZ, {10 * i + 4, RegisterType::kUint32, orders[i], 0.001}}};
    if (i == 0) map.joints.push_back({"A", gcode::kA, {6, RegisterType::kInt16, {}, 0.5}});
    ASSERT_TRUE(validateModbusMap(map).empty());
    ModbusTcpClient client(map, {std::chrono::milliseconds(20), std::chrono::milliseconds(20)});
    // pymodbus accepts connections some 100 ms after it starts
    ModbusSample s;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    for (;;) {
      try {
        s = client.read();
        break;
      } catch (const ModbusError& e) {
        ASSERT_LT(std::chrono::steady_clock::now(), deadline) << e.what();
        std::this_thread::sleep_for(20ms);
      }
    }
    EXPECT_EQ(s.joints[gcode::kX], -123.25) << wordOrderName(orders[i]);
    EXPECT_EQ(s.joints[gcode::kY], -123456.0) << wordOrderName(orders[i]);
    EXPECT_DOUBLE_EQ(s.joints[gcode::kZ], 3000000.0) << wordOrderName(orders[i]);
    if (i == 0) {
      EXPECT_EQ(s.joints[gcode::kA], -1.0);
    }
  }
}

}  // namespace
}  // namespace mdhd::protocol

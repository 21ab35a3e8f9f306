// The simulated controller in-process: the Modbus server with the libmodbus
// client (bad clients, exceptions, a server that dies and comes back, the feed-hold
// coil), and the virtual machine playing a short program through it.
#include <sys/socket.h>

#include <chrono>
#include <sstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include "daemon/modbus_server.h"
#include "daemon/virtual_machine.h"
#include "protocol/modbus_client.h"
#include "sim/gcode/interpreter.h"
#include "sim/kinematics/presets.h"
#include "tests/modbus/modbus_test_peers.h"

namespace mdhd::daemon {
namespace {

using namespace std::chrono_literals;
using protocol::ModbusError;
using protocol::ModbusMap;
using protocol::ModbusSample;
using protocol::ModbusTcpClient;
using Kind = ModbusError::Kind;

const kin::Machine& mill() {
  static const kin::Machine m = kin::presets::threeAxisMill();
  return m;
}

ModbusMap mapOn(int port) {
  ModbusMap map = protocol::defaultModbusMap(mill());  // X Y Z, tool 6, spindle 7, line 8..9
  map.port = port;
  map.timeout_ms = 200;
  return map;
}

std::unique_ptr<ModbusServer> serverFor(const ModbusMap& map, int port = 0) {
  ModbusServerOptions o;
  o.port = port;
  o.registers = protocol::registerSpan(map);
  o.coils = 1;
  return std::make_unique<ModbusServer>(o);
}

void publish(ModbusServer& server, const ModbusMap& map, double x, std::int64_t line) {
  ModbusSample s;
  s.joints[gcode::kX] = x;
  s.joints[gcode::kY] = -2.5;
  s.joints[gcode::kZ] = 300;
  s.tool = 3;
  s.spindle_on = true;
  s.line = line;
  std::vector<std::uint16_t> image(static_cast<std::size_t>(protocol::registerSpan(map)));
  protocol::encodeSample(map, s, image);
  server.setRegisters(image);
}

ModbusSample readWithin(ModbusTcpClient& client, std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  for (;;) {
    try {
      return client.read();
    } catch (const ModbusError& e) {
      if (std::chrono::steady_clock::now() > deadline) throw;
      std::this_thread::sleep_for(5ms);
    }
  }
}

int connectRaw(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  return fd;
}

TEST(ModbusServer, AnswersWithTheInitialRegistersBeforeAnyPublish) {
  const ModbusMap probe = mapOn(0);
  ModbusSample home;
  home.joints[gcode::kZ] = 300;
  home.tool = 0;
  home.spindle_on = false;
  home.line = 0;
  ModbusServerOptions o;
  o.registers = protocol::registerSpan(probe);
  o.initial.resize(static_cast<std::size_t>(o.registers));
  protocol::encodeSample(probe, home, o.initial);
  ModbusServer server(o);
  ModbusTcpClient client(mapOn(server.port()));
  const ModbusSample s = client.read();
  EXPECT_EQ(s.joints[gcode::kZ], 300.0);  // never the all-zero pose
  EXPECT_EQ(s.joints[gcode::kX], 0.0);
  EXPECT_EQ(*s.line, 0);
}

TEST(ModbusSimServer, ServesTheMapAndSurvivesBadClients) {
  ModbusMap map = mapOn(0);
  auto server = serverFor(map);
  map.port = server->port();
  publish(*server, map, 12.25, 42);
  ModbusTcpClient client(map);
  ModbusSample s = client.read();
  EXPECT_EQ(s.joints[gcode::kX], 12.25);
  EXPECT_EQ(s.joints[gcode::kY], -2.5);
  EXPECT_EQ(s.joints[gcode::kZ], 300);
  EXPECT_EQ(s.tool, 3);
  EXPECT_EQ(s.spindle_on, true);
  EXPECT_EQ(s.line, 42);

  // Garbage, a frame cut short and left hanging, a frame cut by a close, and a
  // client that connects and leaves: none of them stops the server.
  const int garbage = connectRaw(server->port());
  modbus_test::sendAll(garbage, modbus_test::Bytes(40, 0xAB));
  const int hanging = connectRaw(server->port());
  modbus_test::sendAll(hanging, modbus_test::Bytes{0, 1, 0, 0, 0, 6, 1, 3});
  const int cut = connectRaw(server->port());
  modbus_test::sendAll(cut, modbus_test::Bytes{0, 1, 0, 0});
  close(cut);
  close(connectRaw(server->port()));
  std::this_thread::sleep_for(20ms);
  publish(*server, map, -7.5, 43);
  for (int i = 0; i < 20; ++i) {
    s = client.read();
    EXPECT_EQ(s.joints[gcode::kX], -7.5);
    EXPECT_EQ(s.line, 43);
  }
  ModbusTcpClient second(map);
  EXPECT_EQ(second.read().line, 43);
  close(garbage);
  close(hanging);
  EXPECT_EQ(server->requests(), 22u);  // garbage and broken frames are not answered
}

TEST(ModbusSimServer, AMapBeyondTheRegistersGetsIllegalAddress) {
  ModbusMap map = mapOn(0);
  auto server = serverFor(map);
  map.port = server->port();
  map.line->address = 20;  // the server has registers 0..9
  ModbusTcpClient client(map);
  try {
    client.read();
    FAIL() << "read beyond the table";
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), Kind::kException);
    EXPECT_EQ(e.code(), EMBXILADD);
    EXPECT_THAT(e.what(), ::testing::HasSubstr("Illegal data address"));
  }
  map.table = protocol::RegisterTable::kInput;  // the server serves holding registers only
  ModbusTcpClient input(map);
  EXPECT_THROW(input.read(), ModbusError);
}

TEST(ModbusSimServer, ClientReconnectsWithBackoffAfterTheServerRestarts) {
  ModbusMap map = mapOn(0);
  auto server = serverFor(map);
  const int port = server->port();
  map.port = port;
  publish(*server, map, 1.0, 1);
  ModbusTcpClient client(map);
  EXPECT_EQ(client.read().line, 1);

  server.reset();  // killed mid-run
  try {
    client.read();
    FAIL() << "read from a stopped server";
  } catch (const ModbusError& e) {
    EXPECT_THAT(e.kind(), ::testing::AnyOf(Kind::kConnectionLost, Kind::kTimeout)) << e.what();
  }
  // While it is down: refused, with a growing backoff.
  std::this_thread::sleep_until(client.nextAttempt() + 1ms);
  try {
    client.read();
    FAIL();
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), Kind::kConnect) << e.what();
  }
  EXPECT_EQ(client.lastWait(), 100ms);

  server = serverFor(map, port);
  publish(*server, map, 2.0, 2);
  const ModbusSample s = readWithin(client, 2s);
  EXPECT_EQ(s.line, 2);
  EXPECT_EQ(s.joints[gcode::kX], 2.0);
  EXPECT_EQ(client.connects(), 2u);
  EXPECT_EQ(client.lastWait(), 0ms);  // reset on success
}

TEST(ModbusSimServer, FeedHoldCoilReachesTheOwner) {
  ModbusMap map = mapOn(0);
  auto server = serverFor(map);
  map.port = server->port();
  ModbusTcpClient client(map);
  EXPECT_FALSE(server->coil(0));
  client.writeFeedHold(true);
  EXPECT_TRUE(server->coil(0));
  client.writeFeedHold(false);
  EXPECT_FALSE(server->coil(0));
  EXPECT_FALSE(server->coil(1));  // no such coil
}

// --- the virtual machine playing a program through the server ---

struct Played {
  std::int64_t line;
  double x, y, z;
  int tool;
  bool spindle;
};

class PlayingMachine {
 public:
  explicit PlayingMachine(const std::string& program, double speed)
      : kin_(mill()), map_(mapOn(0)), server_(serverFor(map_)) {
    map_.port = server_->port();
    job_.machine = mill();
    geom::Tool tool;
    tool.number = 1;
    tool.length = 50;
    tool.diameter = 6;
    job_.tools.push_back(tool);
    image_.resize(static_cast<std::size_t>(protocol::registerSpan(map_)));
    PlaybackHooks hooks;
    hooks.publish = [this](const ControllerState& s) {
      ModbusSample sample;
      sample.joints = s.joints;
      sample.tool = s.tool;
      sample.spindle_on = s.spindle_on;
      sample.line = s.line;
      protocol::encodeSample(map_, sample, image_);
      server_->setRegisters(image_);
    };
    hooks.feed_hold = [this] { return server_->coil(0); };
    hooks.stop_requested = [this] { return stop_.load(); };
    vm_ = std::make_unique<VirtualMachine>(kin_, job_, hooks, speed, log_);
    vm_->reset(mill().home);
    thread_ = std::thread([this, program] {
      gcode::InterpreterConfig config;
      config.home = mill().home;
      config.axis_mask = 0b111;
      config.tools.add({1, 50, 6});
      gcode::Interpreter interp(config, *vm_);
      try {
        interp.run(gcode::makeStringSource(program));
        finished_ = true;
        vm_->holdUntilStopped();
      } catch (const PlaybackStopped&) {
      }
    });
  }
  ~PlayingMachine() {
    stop_ = true;
    thread_.join();
  }
  const ModbusMap& map() const { return map_; }
  bool finished() const { return finished_.load(); }
  std::string log() const { return log_.str(); }

 private:
  kin::Kinematics kin_;
  ModbusMap map_;
  std::unique_ptr<ModbusServer> server_;
  protocol::Job job_;
  std::vector<std::uint16_t> image_;
  std::ostringstream log_;  // written only by the playing thread until it is joined
  std::unique_ptr<VirtualMachine> vm_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  std::thread thread_;
};

Played poll(ModbusTcpClient& client) {
  const ModbusSample s = client.read();
  return {*s.line, s.joints[gcode::kX], s.joints[gcode::kY], s.joints[gcode::kZ],
          *s.tool, *s.spindle_on};
}

// Home is X0 Y0 Z300; tool 1 is 50 long. Machine time: G0 0.98 s (Z's 245 mm at
// 15000), G1 X50 4 s, G1 Y40 3 s: 7.98 s, 0.4 s at speed 20.
const char* kProgram =
    "G21 G90 G54\nT1 M6\nG43 H1\nM3 S1000\nG0 X10 Y10 Z5\nG1 X50 F600\nG1 Y40\nM5\nM30\n";

TEST(ModbusSimPlayback, ClientWatchesTheProgramPlay) {
  PlayingMachine machine(kProgram, 20.0);
  ModbusTcpClient client(machine.map());
  std::vector<Played> seen;
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < 5s) {
    seen.push_back(poll(client));
    if (seen.back().line == 8 && machine.finished()) break;
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(seen.back().line, 8);  // M5
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(elapsed, 7.98 / 20 * 0.8);  // it plays in (scaled) real time, not at once
  EXPECT_EQ(seen.back().x, 50);
  EXPECT_EQ(seen.back().y, 40);
  EXPECT_EQ(seen.back().z, 55);
  EXPECT_EQ(seen.back().tool, 1);
  EXPECT_FALSE(seen.back().spindle);
  int on_x_move = 0;
  int on_y_move = 0;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    const Played& p = seen[i];
    if (i > 0) {
      EXPECT_GE(p.line, seen[i - 1].line);
    }
    if (p.line == 6) {  // G1 X50: Y and Z fixed, X on its way
      ++on_x_move;
      EXPECT_EQ(p.y, 10);
      EXPECT_EQ(p.z, 55);
      EXPECT_GE(p.x, 10);
      EXPECT_LE(p.x, 50);
      EXPECT_TRUE(p.spindle);
      if (i > 0 && seen[i - 1].line == 6) {
        EXPECT_GE(p.x, seen[i - 1].x);
      }
    }
    if (p.line == 7) {
      ++on_y_move;
      EXPECT_EQ(p.x, 50);
      EXPECT_GE(p.y, 10);
      EXPECT_LE(p.y, 40);
    }
  }
  // 0.2 s and 0.15 s of wall time polled every ~1 ms: many samples each
  EXPECT_GT(on_x_move, 20);
  EXPECT_GT(on_y_move, 15);
}

TEST(ModbusSimPlayback, FeedHoldPausesTheMachine) {
  PlayingMachine machine(kProgram, 20.0);
  ModbusTcpClient client(machine.map());
  Played p{};
  const auto t0 = std::chrono::steady_clock::now();
  do {
    p = poll(client);
    ASSERT_LT(std::chrono::steady_clock::now() - t0, 5s);
  } while (!(p.line == 6 && p.x > 12));
  client.writeFeedHold(true);
  std::this_thread::sleep_for(20ms);  // the tick in flight lands
  const Played held = poll(client);
  for (int i = 0; i < 15; ++i) {
    std::this_thread::sleep_for(10ms);
    const Played q = poll(client);
    EXPECT_EQ(q.x, held.x);
    EXPECT_EQ(q.line, 6);
  }
  client.writeFeedHold(false);
  do {
    p = poll(client);
    ASSERT_LT(std::chrono::steady_clock::now() - t0, 5s);
  } while (!machine.finished());
  EXPECT_EQ(poll(client).y, 40);
  EXPECT_THAT(machine.log(), ::testing::HasSubstr("feed hold on at line 6"));
  EXPECT_THAT(machine.log(), ::testing::HasSubstr("feed hold off at line 6"));
}

}  // namespace
}  // namespace mdhd::daemon

// `mdhd modbus-sim` end to end: the binary plays the contour example at --speed 20
// while a libmodbus client watches the line register advance and the joints end
// where `mdhd trace` says; SIGTERM stops it cleanly; bad arguments and maps are
// refused with a clear message.
#include <cstdio>
#include <fstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "protocol/modbus_client.h"
#include "protocol/modbus_map_json.h"
#include "sim/kinematics/presets.h"
#include "tests/modbus/sim_process.h"

namespace mdhd::modbus_test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

const std::string kBin = MDHD_BIN;
const std::string kContour = std::string(MDHD_SHARED_DIR) + "/examples/contour-3axis.json";

// The last line `mdhd trace` prints for a job.
nlohmann::json lastTraceLine(const std::string& job) {
  FILE* pipe = popen((kBin + " trace " + job).c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("popen");
  std::string text;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe) != nullptr) text = buf;
  pclose(pipe);
  return nlohmann::json::parse(text);
}

int listeningPort(SimProcess& sim) {
  const std::string line = sim.readLine(10s);
  const std::string prefix = "listening on 127.0.0.1:";
  if (line.rfind(prefix, 0) != 0) {
    ADD_FAILURE() << "first line: '" << line << "'";
    return -1;
  }
  return std::stoi(line.substr(prefix.size()));
}

protocol::ModbusMap contourMap(int port) {
  protocol::ModbusMap map = protocol::defaultModbusMap(kin::presets::threeAxisMill());
  map.port = port;
  map.timeout_ms = 500;
  return map;
}

// Contour machine time, by hand: G0 to X30 Y25 Z55 0.98 s (Z's 245 mm at 15000),
// G1 Z48 at F300 1.4 s, four 40/20 mm sides at F800 9 s, four R5 quarter arcs
// 4 * 2.5 pi / 800 min = 2.356194 s, G0 Z55 0.028 s: 13.764194 s, 0.688 s at 20x.

TEST(ModbusSimBinary, ContourPlaysAndEndsWhereTraceSays) {
  const nlohmann::json last = lastTraceLine(kContour);
  ASSERT_EQ(last["line"], 16);

  SimProcess sim(
      {kBin, "modbus-sim", kContour, "--port", "0", "--speed", "20", "--exit-after", "30"});
  const int port = listeningPort(sim);
  ASSERT_GT(port, 0);
  protocol::ModbusTcpClient client(contourMap(port));
  std::vector<std::int64_t> lines;
  protocol::ModbusSample s;
  std::chrono::steady_clock::time_point first_feed{};
  std::chrono::steady_clock::time_point done{};
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < 20s) {
    s = client.read();
    const auto now = std::chrono::steady_clock::now();
    if (lines.empty() || lines.back() != *s.line) lines.push_back(*s.line);
    if (*s.line >= 7 && first_feed == std::chrono::steady_clock::time_point{}) first_feed = now;
    if (*s.line == 17) {  // M5: the program is over
      done = now;
      break;
    }
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(lines.back(), 17) << "the program did not finish";
  // Every feed motion (29 ms or more at 20x) was seen, in program order.
  for (std::size_t i = 1; i < lines.size(); ++i) EXPECT_GT(lines[i], lines[i - 1]);
  for (int line = 7; line <= 15; ++line) {
    EXPECT_NE(std::find(lines.begin(), lines.end(), line), lines.end()) << "line " << line;
  }
  // Real time at 20x: from the plunge (line 7) to the end, 12.784 s / 20 = 0.64 s.
  const double played = std::chrono::duration<double>(done - first_feed).count();
  EXPECT_GT(played, 0.5);
  EXPECT_LT(played, 1.5);
  // The pose it holds is the last one `mdhd trace` prints.
  std::this_thread::sleep_for(50ms);
  s = client.read();
  EXPECT_EQ(s.joints[gcode::kX], last["joints"]["X"].get<double>());
  EXPECT_EQ(s.joints[gcode::kY], last["joints"]["Y"].get<double>());
  EXPECT_EQ(s.joints[gcode::kZ], last["joints"]["Z"].get<double>());
  EXPECT_EQ(s.tool, 1);
  EXPECT_EQ(s.spindle_on, false);

  EXPECT_EQ(sim.stop(SIGTERM, 3s), 0);
  const std::string errors = sim.errors();
  EXPECT_THAT(errors, HasSubstr("program finished (13.764 s of machine time)"));
}

TEST(ModbusSimBinary, MapFileFeedHoldAndExitAfter) {
  // Joints as int32 dcba in micrometres from the input table, like some controllers.
  const std::string map_path = ::testing::TempDir() + "modbus_sim_map.json";
  {
    std::ofstream out(map_path);
    out << R"({"host": "127.0.0.1", "table": "input",
      "joints": {"X": {"address": 100, "type": "int32", "word_order": "dcba", "scale": 0.001},
                 "Y": {"address": 102, "type": "int32", "word_order": "dcba", "scale": 0.001},
                 "Z": {"address": 104, "type": "int32", "word_order": "dcba", "scale": 0.001}},
      "line": {"address": 0, "type": "uint16"},
      "feed_hold": {"coil": 3}})";
  }
  SimProcess sim({kBin, "modbus-sim", kContour, "--port", "0", "--speed", "20", "--map", map_path,
                  "--exit-after", "1.5"});
  const int port = listeningPort(sim);
  ASSERT_GT(port, 0);
  std::ifstream in(map_path);
  protocol::ModbusMap map = protocol::modbusMapFromJson(nlohmann::json::parse(in));
  map.port = port;
  protocol::ModbusTcpClient client(map);
  protocol::ModbusSample s;
  do {
    s = client.read();
  } while (*s.line < 8);
  client.writeFeedHold(true);
  std::this_thread::sleep_for(30ms);
  const double x = client.read().joints[gcode::kX];
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(client.read().joints[gcode::kX], x);
  client.writeFeedHold(false);
  // --exit-after 1.5: it leaves by itself, cleanly.
  EXPECT_EQ(sim.stop(0, 6s), 0);
  const std::string errors = sim.errors();
  EXPECT_THAT(errors, HasSubstr("feed hold on at line 8"));
  EXPECT_THAT(errors, HasSubstr("feed hold off at line 8"));
  EXPECT_THROW(client.read(), protocol::ModbusError);  // the server is gone
}

TEST(ModbusSimBinary, JobsOwnModbusBlockAndLoop) {
  // A job carrying its own `modbus` block: joints as float32 cdab from address 50.
  const std::string examples = std::string(MDHD_SHARED_DIR) + "/examples/";
  nlohmann::json job = nlohmann::json::parse(std::ifstream(kContour));
  job["machine_file"] = examples + "machine-3axis.json";
  job["program_file"] = examples + "contour-3axis.ngc";
  job["modbus"] = nlohmann::json::parse(R"({"host": "127.0.0.1",
      "joints": {"X": {"address": 50, "type": "float32", "word_order": "cdab"},
                 "Y": {"address": 52, "type": "float32", "word_order": "cdab"},
                 "Z": {"address": 54, "type": "float32", "word_order": "cdab"}},
      "line": {"address": 56, "type": "uint32", "word_order": "cdab"}})");
  const std::string job_path = ::testing::TempDir() + "modbus_sim_job.json";
  std::ofstream(job_path) << job.dump();

  SimProcess sim({kBin, "modbus-sim", job_path, "--port", "0", "--speed", "40", "--loop",
                  "--exit-after", "10"});
  const int port = listeningPort(sim);
  ASSERT_GT(port, 0);
  protocol::ModbusMap map = protocol::modbusMapFromJson(job["modbus"]);
  map.port = port;
  protocol::ModbusTcpClient client(map);
  // --loop: after the last line the program starts again from home.
  std::int64_t highest = 0;
  bool restarted = false;
  const auto t0 = std::chrono::steady_clock::now();
  while (!restarted && std::chrono::steady_clock::now() - t0 < 8s) {
    const protocol::ModbusSample s = client.read();
    if (*s.line == 8) {  // G1 X70 at Y25, Z48
      EXPECT_EQ(s.joints[gcode::kY], 25);
      EXPECT_EQ(s.joints[gcode::kZ], 48);
    }
    restarted = highest >= 15 && *s.line < 8;  // line 15 is the last arc (15 ms at 40x)
    highest = std::max(highest, *s.line);
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_TRUE(restarted);
  EXPECT_EQ(sim.stop(SIGINT, 3s), 0);
  const std::string errors = sim.errors();
  EXPECT_THAT(errors, HasSubstr("program finished (13.764 s of machine time)"));
}

struct Refusal {
  std::vector<std::string> args;
  std::string message;
};

TEST(ModbusSimBinary, RefusesBadArgumentsAndMaps) {
  const std::string bad_map = ::testing::TempDir() + "modbus_sim_bad_map.json";
  {
    std::ofstream out(bad_map);
    out << R"({"host": "h", "joints": {"X": {"address": 0, "type": "float32"},
      "Y": {"address": 1, "type": "float32"}, "Z": {"address": 4, "type": "float32"}}})";
  }
  const std::string no_z = ::testing::TempDir() + "modbus_sim_no_z.json";
  {
    std::ofstream out(no_z);
    out << R"({"modbus": {"host": "h", "joints": {"X": {"address": 0, "type": "float32"}}}})";
  }
  const Refusal cases[] = {
      {{"modbus-sim", kContour}, "--port is required"},
      {{"modbus-sim", kContour, "--port", "70000"}, "--port expects 0..65535"},
      {{"modbus-sim", kContour, "--port", "0", "--speed", "0"}, "--speed expects > 0"},
      {{"modbus-sim", kContour, "--port", "0", "--speed", "fast"}, "--speed expects a number"},
      {{"modbus-sim", "/nonexistent/job.json", "--port", "0"}, "cannot open /nonexistent/job.json"},
      {{"modbus-sim", kContour, "--port", "0", "--map", bad_map},
       "modbus.joints.Y.address: registers 1..2 overlap joints.X (registers 0..1)"},
      {{"modbus-sim", kContour, "--port", "0", "--map", no_z},
       "modbus.joints: the machine's joint Y has no register"},
      {{"modbus-sim", kContour, "--port", "0", "--host", "not-an-ip"},
       "'not-an-ip' is not an IPv4 address"},
  };
  for (const Refusal& r : cases) {
    std::vector<std::string> args = {kBin};
    args.insert(args.end(), r.args.begin(), r.args.end());
    SimProcess sim(args);
    EXPECT_EQ(sim.stop(0, 5s), 2) << r.message;
    EXPECT_THAT(sim.errors(), HasSubstr(r.message));
  }
}

}  // namespace
}  // namespace mdhd::modbus_test

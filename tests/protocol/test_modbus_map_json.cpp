// The `modbus` block's JSON codec: the contract's example, defaults, and one
// error per kind of mistake, each naming the field's path.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "protocol/job_json.h"
#include "protocol/modbus_map_json.h"
#include "sim/kinematics/presets.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;

// service.md's example, verbatim.
const char* kContractExample = R"({
    "host": "127.0.0.1", "port": 502, "unit_id": 1,
    "poll_hz": 50, "timeout_ms": 200,
    "table": "holding",
    "joints": {
      "X": { "address": 0, "type": "float32", "word_order": "abcd", "scale": 1.0 },
      "Y": { "address": 2, "type": "float32" },
      "Z": { "address": 4, "type": "float32" },
      "A": { "address": 6, "type": "float32" },
      "C": { "address": 8, "type": "float32" }
    },
    "tool": { "address": 10, "type": "uint16" },
    "spindle_on": { "address": 11, "type": "uint16" },
    "line": { "address": 12, "type": "uint32" },
    "feed_hold": { "coil": 0, "enabled": false }
  })";

json example() {
  return json::parse(kContractExample);
}

const RegisterField& joint(const ModbusMap& map, const std::string& name) {
  for (const auto& j : map.joints) {
    if (j.name == name) return j.field;
  }
  throw std::runtime_error("no joint " + name);
}

TEST(ModbusMapJson, ReadsTheContractExample) {
  const kin::Machine ac = kin::presets::acTrunnion();
  const ModbusMap map = modbusMapFromJson(example(), "modbus", &ac);
  EXPECT_EQ(map.host, "127.0.0.1");
  EXPECT_EQ(map.port, 502);
  EXPECT_EQ(map.unit_id, 1);
  EXPECT_EQ(map.poll_hz, 50.0);
  EXPECT_EQ(map.timeout_ms, 200);
  EXPECT_EQ(map.table, RegisterTable::kHolding);
  ASSERT_EQ(map.joints.size(), 5u);
  EXPECT_EQ(joint(map, "C").address, 8);
  EXPECT_EQ(joint(map, "A").address, 6);
  EXPECT_EQ(map.tool->address, 10);
  EXPECT_EQ(map.line->type, RegisterType::kUint32);
  EXPECT_FALSE(map.feed_hold.enabled);
  EXPECT_EQ(planReads(map).size(), 1u);
}

TEST(ModbusMapJson, DefaultsAndRoundTrip) {
  const json j = json::parse(R"({"host": "cnc.local", "table": "input",
      "joints": {"X": {"address": 100, "type": "int32", "word_order": "cdab", "scale": 0.001}}})");
  const ModbusMap map = modbusMapFromJson(j);
  EXPECT_EQ(map.port, 502);
  EXPECT_EQ(map.unit_id, 1);
  EXPECT_EQ(map.poll_hz, 50.0);
  EXPECT_EQ(map.timeout_ms, 200);
  EXPECT_EQ(map.table, RegisterTable::kInput);
  EXPECT_EQ(map.joints[0].field.word_order, WordOrder::kCdab);
  EXPECT_EQ(map.joints[0].field.scale, 0.001);
  EXPECT_FALSE(map.tool.has_value());
  EXPECT_EQ(map.feed_hold.coil, 0);
  const json back = modbusMapToJson(map);
  EXPECT_EQ(back["joints"]["X"]["word_order"], "cdab");
  EXPECT_EQ(back["table"], "input");
  EXPECT_EQ(modbusMapToJson(modbusMapFromJson(back)), back);
  const json ex = modbusMapToJson(modbusMapFromJson(example()));
  EXPECT_EQ(modbusMapToJson(modbusMapFromJson(ex)), ex);
  EXPECT_FALSE(ex["tool"].contains("word_order"));  // 16-bit: no word order
}

std::string mapErrorOf(const json& j, const kin::Machine* machine = nullptr) {
  try {
    modbusMapFromJson(j, "modbus", machine);
  } catch (const FieldError& e) {
    return e.what();
  }
  return "(accepted)";
}

json with(const std::string& pointer, const json& value) {
  json j = example();
  j[json::json_pointer(pointer)] = value;
  return j;
}

json without(const std::string& key) {
  json j = example();
  j.erase(key);
  return j;
}

TEST(ModbusMapJson, ErrorsNameTheField) {
  EXPECT_EQ(mapErrorOf(with("/joints/X/word_order", "bacd")),
            "modbus.joints.X.word_order: expected one of abcd, badc, cdab, dcba, got the string "
            "\"bacd\"");
  EXPECT_EQ(mapErrorOf(with("/joints/Y/type", "float64")),
            "modbus.joints.Y.type: expected one of float32, int32, uint32, int16, uint16, got the "
            "string \"float64\"");
  EXPECT_EQ(mapErrorOf(with("/tool/word_order", "cdab")),
            "modbus.tool.word_order: applies to 32-bit types only, not to uint16");
  EXPECT_EQ(mapErrorOf(with("/joints/Z/address", 3)),
            "modbus.joints.Z.address: registers 3..4 overlap joints.Y (registers 2..3)");
  EXPECT_EQ(mapErrorOf(with("/line/address", 65535)),
            "modbus.line.address: registers 65535..65536 (a uint32) is outside 0..65535");
  EXPECT_EQ(mapErrorOf(with("/joints/X/adress", 0)),
            "modbus.joints.X.adress: unknown field (known: address, type, word_order, scale)");
  EXPECT_EQ(mapErrorOf(with("/joints/Q", json{{"address", 20}, {"type", "float32"}})),
            "modbus.joints.Q: is not a joint name (X Y Z A B C U V W)");
  EXPECT_EQ(mapErrorOf(with("/poll_hz", 5000)),
            "modbus.poll_hz: must be in 0.1..1000 (polls per second)");
  EXPECT_EQ(mapErrorOf(with("/poll_hz", "fast")),
            "modbus.poll_hz: expected a number, got the string \"fast\"");
  EXPECT_EQ(mapErrorOf(with("/table", "coils")),
            "modbus.table: expected \"holding\" or \"input\", got the string \"coils\"");
  EXPECT_EQ(mapErrorOf(with("/feed_hold/enabled", 1)),
            "modbus.feed_hold.enabled: expected true or false, got the number 1");
  EXPECT_EQ(mapErrorOf(with("/timeout_ms", 0.5)),
            "modbus.timeout_ms: expected an integer, got the number 0.5");
  EXPECT_EQ(mapErrorOf(with("/joints/X/scale", 0)),
            "modbus.joints.X.scale: must be a finite number other than 0");
  EXPECT_EQ(mapErrorOf(without("host")), "modbus.host: missing");
  EXPECT_EQ(mapErrorOf(without("joints")), "modbus.joints: missing");
  EXPECT_EQ(mapErrorOf(with("/joints", json::object())),
            "modbus.joints: must map at least one joint");
  EXPECT_EQ(mapErrorOf(with("/joints/X", json{{"type", "float32"}})),
            "modbus.joints.X.address: missing");
  EXPECT_EQ(mapErrorOf(with("/joints", json::array())),
            "modbus.joints: expected an object of joint name -> register, got an array of 0");
  EXPECT_EQ(mapErrorOf(json::array()), "modbus: expected an object, got an array of 0");
}

TEST(ModbusMapJson, HostMustBeAHostNameOrAddress) {
  EXPECT_EQ(mapErrorOf(with("/host", std::string("cnc\0evil", 8))),
            "modbus.host: must be a host name or address: no spaces or control characters");
  EXPECT_EQ(mapErrorOf(with("/host", "cnc local")),
            "modbus.host: must be a host name or address: no spaces or control characters");
  EXPECT_EQ(mapErrorOf(with("/host", std::string(100'000, 'a'))),
            "modbus.host: is 100000 characters long: a host name or address has at most 253");
  EXPECT_EQ(mapErrorOf(with("/host", "")), "modbus.host: must name the controller (not empty)");
  EXPECT_EQ(mapErrorOf(with("/host", std::string(253, 'a'))), "(accepted)");
  EXPECT_EQ(mapErrorOf(with("/host", "fe80::1")), "(accepted)");
}

TEST(ModbusMapJson, JointNamesMustBeTheMachines) {
  const kin::Machine bc = kin::presets::bcHeadTable();  // X Y Z B C
  EXPECT_EQ(mapErrorOf(example(), &bc),
            "modbus.joints.A: the machine has no joint A (it has XYZBC)");
  json j = example();
  j["joints"]["B"] = j["joints"]["A"];
  j["joints"].erase("A");
  EXPECT_EQ(mapErrorOf(j, &bc), "(accepted)");
  j["joints"].erase("C");
  EXPECT_EQ(mapErrorOf(j, &bc),
            "modbus.joints: the machine's joint C has no register (every joint must be read for "
            "a pose)");
}

}  // namespace
}  // namespace mdhd::protocol

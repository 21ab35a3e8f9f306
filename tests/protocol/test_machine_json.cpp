// The machine codec: every example machine round-trips, its poses come out as the
// examples' README says, and each kind of bad input gets its own message.
#include "protocol/machine_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>

#include "sim/kinematics/kinematics.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;

json readExample(const std::string& name) {
  std::ifstream in(std::string(MDHD_SHARED_DIR) + "/examples/" + name);
  EXPECT_TRUE(in) << name;
  return json::parse(in);
}

TEST(MachineJson, ExampleMachinesRoundTripExactly) {
  for (const char* file :
       {"machine-3axis.json", "machine-ac-trunnion.json", "machine-bc-head-table.json"}) {
    const json original = readExample(file);
    const kin::Machine m = machineFromJson(original);
    // The examples write every field the codec writes, so the JSON comes back as it was.
    EXPECT_EQ(machineToJson(m), original) << file;
    EXPECT_EQ(machineToJson(machineFromJson(machineToJson(m))), original) << file;
  }
}

TEST(MachineJson, ExampleMachineContents) {
  const kin::Machine m = machineFromJson(readExample("machine-bc-head-table.json"));
  EXPECT_EQ(m.name, "B swivel head, C rotary table centred at (2, 2)");
  ASSERT_EQ(m.joints.size(), 5u);
  EXPECT_EQ(m.joints[3].name, "B");
  EXPECT_EQ(m.joints[3].type, kin::JointType::kRotary);
  ASSERT_TRUE(m.joints[3].limits);
  EXPECT_EQ(m.joints[3].limits->min, -110);
  EXPECT_FALSE(m.joints[4].limits);
  EXPECT_EQ(m.joints[4].origin, glm::dvec3(2, 2, 0));
  EXPECT_EQ(m.tool_chain, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(m.workpiece_chain, (std::vector<int>{4}));
  EXPECT_EQ(m.home[gcode::kX], -30);
  EXPECT_EQ(m.home[gcode::kZ], 40);
  EXPECT_EQ(m.rapid_feed, 10000);
  EXPECT_EQ(m.max_feed, 5000);
}

TEST(MachineJson, DonutPoseOnTheExampleMachine) {
  // README: B-25 C0, machine X-4.76237 Y2 Z18.80096, tool length 20:
  // tip (3.69, 2, 0.6748), axis (-sin 25, 0, cos 25) in W.
  const kin::Kinematics kin(machineFromJson(readExample("machine-bc-head-table.json")));
  kin::JointValues q{};
  q[gcode::kX] = -4.76237;
  q[gcode::kY] = 2;
  q[gcode::kZ] = 18.80096;
  q[gcode::kB] = -25;
  const kin::ToolPose p = kin.toolPose(q, 20);
  const double s = std::sin(25 * std::numbers::pi / 180);
  const double c = std::cos(25 * std::numbers::pi / 180);
  EXPECT_NEAR(p.tip.x, 3.69, 1e-5);
  EXPECT_NEAR(p.tip.y, 2, 1e-12);
  EXPECT_NEAR(p.tip.z, 0.6748, 1e-5);
  EXPECT_NEAR(p.axis.x, -s, 1e-12);
  EXPECT_NEAR(p.axis.y, 0, 1e-12);
  EXPECT_NEAR(p.axis.z, c, 1e-12);
}

TEST(MachineJson, SideDrillPoseOnTheExampleMachine) {
  // README: A-90 C0, G43 length 60, programmed X0 Y15 Z5 -> Z joint 65: tip (0, -5, 15),
  // axis (0, -1, 0).
  const kin::Kinematics kin(machineFromJson(readExample("machine-ac-trunnion.json")));
  kin::JointValues q{};
  q[gcode::kY] = 15;
  q[gcode::kZ] = 5 + 60;
  q[gcode::kA] = -90;
  const kin::ToolPose p = kin.toolPose(q, 60);
  EXPECT_NEAR(p.tip.x, 0, 1e-12);
  EXPECT_NEAR(p.tip.y, -5, 1e-12);
  EXPECT_NEAR(p.tip.z, 15, 1e-12);
  EXPECT_NEAR(p.axis.y, -1, 1e-15);
}

// Applies `edit` to the AC example and returns the error message (or "no error").
template <typename Edit>
std::string errorOf(Edit edit) {
  json j = readExample("machine-ac-trunnion.json");
  edit(j);
  try {
    machineFromJson(j);
  } catch (const MachineJsonError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MachineJson, TypeErrorsNameTheField) {
  EXPECT_EQ(errorOf([](json& j) {
              j["joints"][3]["axis"] = {1, 0};
            }),
            "machine.joints[3].axis: expected an array of 3 numbers, got an array of 2");
  EXPECT_EQ(errorOf([](json& j) {
              j["joints"][3]["axis"] = {1, "0", 0};
            }),
            "machine.joints[3].axis[1]: expected a number, got the string \"0\"");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][0]["origin"] = "here"; }),
            "machine.joints[0].origin: expected an array of 3 numbers, got the string \"here\"");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][1]["type"] = "prismatic"; }),
            "machine.joints[1].type: expected \"linear\" or \"rotary\", got the string "
            "\"prismatic\"");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][1]["name"] = 7; }),
            "machine.joints[1].name: expected a string, got the number 7");
  EXPECT_EQ(errorOf([](json& j) {
              j["joints"][2]["limits"] = {1, 2, 3};
            }),
            "machine.joints[2].limits: expected an array of 2 numbers [min, max], got an "
            "array of 3");
  EXPECT_EQ(errorOf([](json& j) { j["joints"] = json::object(); }),
            "machine.joints: expected an array of joints, got an object");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][4] = 5; }),
            "machine.joints[4]: expected an object, got the number 5");
  EXPECT_EQ(errorOf([](json& j) { j["rapid_feed"] = true; }),
            "machine.rapid_feed: expected a number, got true");
  EXPECT_EQ(errorOf([](json& j) { j["spindle_axis"] = nullptr; }),
            "machine.spindle_axis: expected an array of 3 numbers, got null");
  EXPECT_EQ(errorOf([](json& j) {
              j["home"] = {1, 2};
            }),
            "machine.home: expected an object of joint values, got an array of 2");
  EXPECT_EQ(errorOf([](json& j) { j["home"]["Z"] = "300"; }),
            "machine.home.Z: expected a number, got the string \"300\"");
  EXPECT_EQ(errorOf([](json& j) { j["tool_chain"] = "XYZ"; }),
            "machine.tool_chain: expected an array of joint names, got the string \"XYZ\"");
  EXPECT_EQ(errorOf([](json& j) { j = json::array(); }),
            "machine: expected an object, got an array of 0");
}

TEST(MachineJson, MissingAndUnknownFields) {
  EXPECT_EQ(errorOf([](json& j) { j.erase("max_feed"); }), "machine.max_feed: missing");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][2].erase("axis"); }),
            "machine.joints[2].axis: missing");
  EXPECT_EQ(errorOf([](json& j) {
              j["spindle_axes"] = {0, 0, 1};
            }),
            "machine.spindle_axes: unknown field (known: name, joints, tool_chain, "
            "workpiece_chain, home, spindle_axis, rapid_feed, max_feed)");
  EXPECT_EQ(errorOf([](json& j) {
              j["joints"][3]["limit"] = {0, 1};
            }),
            "machine.joints[3].limit: unknown field (known: name, type, axis, origin, limits)");
  // Optional fields may be left out.
  EXPECT_EQ(errorOf([](json& j) {
              j.erase("name");
              j.erase("home");
              j["joints"][3].erase("origin");
              j["joints"][3].erase("limits");
            }),
            "no error");
}

TEST(MachineJson, NamesAndChains) {
  EXPECT_EQ(errorOf([](json& j) { j["tool_chain"][1] = "Q"; }),
            "machine.tool_chain[1]: unknown joint \"Q\"");
  EXPECT_EQ(errorOf([](json& j) { j["workpiece_chain"].push_back("X"); }),
            "machine.workpiece_chain[2]: joint X is already in the tool_chain; a joint "
            "belongs to one chain only");
  EXPECT_EQ(errorOf([](json& j) { j["workpiece_chain"] = {"A"}; }),
            "machine.joints[4]: joint C is in neither tool_chain nor workpiece_chain");
  EXPECT_EQ(errorOf([](json& j) { j["home"]["B"] = 0; }),
            "machine.home.B: the machine has no joint B");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][4]["name"] = "A"; }),
            "machine.joints[4].name: duplicate joint name A (also joints[3])");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][4]["name"] = "Rot"; }),
            "machine.workpiece_chain[1]: unknown joint \"C\"");
}

TEST(MachineJson, ValuesThatValidationRejects) {
  EXPECT_EQ(errorOf([](json& j) {
              j["joints"][3]["limits"] = {30, -120};
            }),
            "machine.joints[3].limits: min 30 is above max -120");
  EXPECT_EQ(errorOf([](json& j) {
              j["joints"][0]["axis"] = {0, 0, 0};
            }),
            "machine.joints[0].axis: must be a finite, non-zero direction");
  EXPECT_EQ(errorOf([](json& j) { j["joints"][3]["type"] = "linear"; }),
            "machine.joints[3].type: joint A must be rotary (A B C are rotary axes)");
  EXPECT_EQ(errorOf([](json& j) { j["max_feed"] = 0; }),
            "machine.max_feed: must be a positive number (mm/min)");
}

TEST(MachineJson, PathPrefixIsTheCallers) {
  json j = readExample("machine-3axis.json");
  j["joints"][0]["axis"] = "x";
  try {
    machineFromJson(j, "job.machine");
    FAIL();
  } catch (const MachineJsonError& e) {
    EXPECT_EQ(e.field(), "job.machine.joints[0].axis");
  }
}

}  // namespace
}  // namespace mdhd::protocol

namespace mdhd::protocol {
namespace {

// Replaces one random node of j (or removes or adds a key) with a random value.
void mutate(json& j, std::mt19937& rng) {
  json* node = &j;
  while ((node->is_object() || node->is_array()) && !node->empty() && rng() % 3 != 0) {
    auto it = node->begin();
    std::advance(it, static_cast<long>(rng() % node->size()));
    node = &*it;
  }
  switch (rng() % 8) {
    case 0:
      *node = nullptr;
      break;
    case 1:
      *node = static_cast<double>(static_cast<int>(rng() % 2001) - 1000) / 7.0;
      break;
    case 2:
      *node = std::string(1, "XYZABCUVWQx"[rng() % 11]);
      break;
    case 3:
      *node = json::array({1, 0, 0});
      break;
    case 4:
      *node = json::object();
      break;
    case 5:
      *node = (rng() % 2) == 0;
      break;
    case 6:
      if (node->is_object()) (*node)["extra"] = 1;
      break;
    default:
      if (node->is_array() && !node->empty()) node->erase(node->size() - 1);
      break;
  }
}

TEST(MachineJson, MutatedMachinesFailCleanlyOrWork) {
  std::mt19937 rng(3);
  const std::vector<json> bases = {readExample("machine-3axis.json"),
                                   readExample("machine-ac-trunnion.json"),
                                   readExample("machine-bc-head-table.json")};
  int accepted = 0;
  for (int i = 0; i < 3000; ++i) {
    json j = bases[static_cast<std::size_t>(i) % bases.size()];
    for (unsigned k = 0; k <= rng() % 3; ++k) mutate(j, rng);
    try {
      const kin::Machine m = machineFromJson(j);
      ++accepted;
      EXPECT_NO_THROW(kin::Kinematics{m}) << j.dump();
      EXPECT_EQ(machineToJson(machineFromJson(machineToJson(m))), machineToJson(m));
    } catch (const MachineJsonError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("machine", 0), 0u) << e.what();
    }
  }
  // Some mutations keep the machine valid (a new name, a changed limit): both paths run.
  EXPECT_GT(accepted, 50);
  EXPECT_LT(accepted, 2900);
}

}  // namespace
}  // namespace mdhd::protocol

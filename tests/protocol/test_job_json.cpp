// The job document codec: every example job reads, and each kind of mistake is
// reported at the field where it is.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "protocol/job_json.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;

json minimalJob() {
  return json::parse(R"({
    "machine_file": "machine-3axis.json",
    "tools": [{"number": 1, "shape": "flat", "diameter": 6, "flute_length": 20, "length": 50,
               "shank_diameter": 6, "holder": [{"diameter": 30, "length": 25}]}],
    "stock": {"box": {"min": [0, 0, -40], "max": [100, 80, 0]}},
    "program": "G0 X0\nM2\n"
  })");
}

std::string fieldOfError(const json& j) {
  try {
    jobFromJson(j);
  } catch (const FieldError& e) {
    return e.field();
  }
  return "(no error)";
}

TEST(JobJson, ReadsEveryExampleJob) {
  for (const char* name : {"contour-3axis", "crash-3axis", "side-drill-ac", "donut-bc"}) {
    std::ifstream in(std::string(MDHD_SHARED_DIR) + "/examples/" + name + ".json");
    ASSERT_TRUE(in) << name;
    std::stringstream text;
    text << in.rdbuf();
    const Job job = jobFromJson(parseJsonText(text.str()));
    EXPECT_FALSE(job.machine_file.empty()) << name;
    EXPECT_FALSE(job.program_file.empty()) << name;
    EXPECT_EQ(job.tools.size(), 1u) << name;
  }
}

TEST(JobJson, Defaults) {
  const Job job = jobFromJson(minimalJob());
  EXPECT_DOUBLE_EQ(job.options.density, 10.0);
  EXPECT_EQ(job.options.steps, 0);
  EXPECT_DOUBLE_EQ(job.options.tolerance, 0.01);
  EXPECT_EQ(job.options.ruleset, (std::vector<std::string>{"FEFS-FFS", "CTD", "SPT", "RS"}));
  EXPECT_EQ(job.options.seed, 1u);
  EXPECT_TRUE(job.options.three_way);
  EXPECT_DOUBLE_EQ(job.options.contactTolerance(), 0.05);
  EXPECT_DOUBLE_EQ(job.options.chainTolerance(), 0.005);
  EXPECT_EQ(job.stock.lo.z, -40.0);
  EXPECT_EQ(job.stock.hi.x, 100.0);
  for (const auto& w : job.work_offsets) EXPECT_EQ(w, (std::array<double, 3>{0, 0, 0}));
}

TEST(JobJson, ChainToleranceIsAtMostTheTolerance) {
  json j = minimalJob();
  j["options"] = {{"tolerance", 0.02}, {"chain_tolerance", 0.0}};
  EXPECT_DOUBLE_EQ(jobFromJson(j).options.chainTolerance(), 0.0);
  j["options"]["chain_tolerance"] = 0.02;
  EXPECT_DOUBLE_EQ(jobFromJson(j).options.chainTolerance(), 0.02);
  j["options"].erase("chain_tolerance");
  EXPECT_DOUBLE_EQ(jobFromJson(j).options.chainTolerance(), 0.01);  // half the tolerance
  for (const json& bad : {json(-0.001), json(0.03), json("x")}) {
    j["options"]["chain_tolerance"] = bad;
    EXPECT_EQ(fieldOfError(j), "options.chain_tolerance") << bad;
  }
}

TEST(JobJson, TwoSidedMapsAreAnOptionOfThreeWayMaps) {
  EXPECT_TRUE(jobFromJson(minimalJob()).options.two_sided);  // the default
  json j = minimalJob();
  j["options"]["three_way"] = false;  // plain heightmaps are one-sided unless asked
  EXPECT_FALSE(jobFromJson(j).options.two_sided);
  j["options"]["three_way"] = true;
  j["options"]["two_sided"] = false;
  EXPECT_FALSE(jobFromJson(j).options.two_sided);
  j["options"]["two_sided"] = true;
  EXPECT_TRUE(jobFromJson(j).options.two_sided);
  j["options"]["three_way"] = false;
  try {
    jobFromJson(j);
    FAIL() << "two_sided without three_way accepted";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "options.two_sided");
  }
  j["options"]["two_sided"] = "yes";
  EXPECT_THROW(jobFromJson(j), FieldError);
}

TEST(JobJson, WorkOffsetsAndFixtures) {
  json j = minimalJob();
  j["work_offsets"] = {{"G55", {1, 2, 3}}, {"G59.3", {-4, 5, -6}}};
  j["fixtures"] = json::parse(R"([{"box": {"min": [-10, -10, -60], "max": [110, 90, -40]}},
    {"cylinder": {"base": [1, 2, 3], "axis": [0, 0, 2], "radius": 4, "height": 5}}])");
  const Job job = jobFromJson(j);
  EXPECT_EQ(job.work_offsets[1], (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(job.work_offsets[8], (std::array<double, 3>{-4, 5, -6}));
  ASSERT_EQ(job.fixtures.size(), 2u);
  EXPECT_EQ(job.fixtures[0].kind, Fixture::Kind::kBox);
  EXPECT_EQ(job.fixtures[1].kind, Fixture::Kind::kCylinder);
  EXPECT_DOUBLE_EQ(job.fixtures[1].axis.z, 1.0);  // normalised
}

// A grid spacing longer than a side of the stock would resize that side by most of a
// spacing (the engine snaps the max corner to the grid): refused, saying what density fits.
TEST(JobJson, GridSpacingLongerThanAStockSideIsRefused) {
  json j = minimalJob();  // 100 x 80 x 40 mm
  j["options"] = {{"density", 0.001}};
  try {
    jobFromJson(j);
    ADD_FAILURE() << "a 1000 mm grid spacing on a 40 mm stock was accepted";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "options.density");
    EXPECT_NE(e.message().find("along z"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("at least 0.025 points/mm"), std::string::npos) << e.message();
  }
  j["options"] = {{"density", 0.025}};  // exactly one spacing along z
  EXPECT_NO_THROW(jobFromJson(j));
  j["stock"]["box"]["min"][2] = -0.05;  // a 0.05 mm sheet at the default 10 points/mm
  j.erase("options");
  EXPECT_EQ(fieldOfError(j), "options.density");
}

TEST(JobJson, ErrorsNameTheField) {
  json j = minimalJob();
  j["stock"]["box"]["max"][2] = -50;
  EXPECT_EQ(fieldOfError(j), "stock.box");

  j = minimalJob();
  j["options"] = {{"density", -1}};
  EXPECT_EQ(fieldOfError(j), "options.density");

  j = minimalJob();
  j["options"] = {{"ruleset", {"FEFS-FFS", "XYZ"}}};
  EXPECT_EQ(fieldOfError(j), "options.ruleset[1]");

  j = minimalJob();
  j["options"] = {{"densty", 5}};
  EXPECT_EQ(fieldOfError(j), "options.densty");

  j = minimalJob();
  j["work_offsets"] = {{"G60", {0, 0, 0}}};
  EXPECT_EQ(fieldOfError(j), "work_offsets.G60");

  j = minimalJob();
  j["tools"][0]["diameter"] = "six";
  EXPECT_EQ(fieldOfError(j), "tools[0].diameter");

  j = minimalJob();
  j["tools"].push_back(j["tools"][0]);
  EXPECT_EQ(fieldOfError(j), "tools[1].number");

  j = minimalJob();
  j.erase("program");
  EXPECT_EQ(fieldOfError(j), "program");

  j = minimalJob();
  j["machine"] = {{"name", "x"}};
  EXPECT_EQ(fieldOfError(j), "machine");  // both machine and machine_file

  j = minimalJob();
  j["fixtures"] = json::parse(
      R"([{"cylinder": {"base": [0,0,0], "axis": [0,0,0], "radius": 1, "height": 1}}])");
  EXPECT_EQ(fieldOfError(j), "fixtures[0].cylinder.axis");

  j = minimalJob();
  j["options"] = {{"seed", -3}};
  EXPECT_EQ(fieldOfError(j), "options.seed");
}

TEST(JobJson, MachineByNameIsKept) {
  json j = minimalJob();
  j.erase("machine_file");
  j["machine"] = "3-axis vertical mill";
  EXPECT_EQ(jobFromJson(j).machine_name, "3-axis vertical mill");
}

TEST(JobJson, ModbusBlockIsKeptForTheModbusCodec) {
  json j = minimalJob();
  j["modbus"] = {{"host", "127.0.0.1"}, {"joints", {{"X", {{"address", 0}}}}}};
  const Job job = jobFromJson(j);
  ASSERT_TRUE(job.modbus.has_value());
  EXPECT_EQ((*job.modbus)["host"], "127.0.0.1");
  j["modbus"] = 5;
  EXPECT_EQ(fieldOfError(j), "modbus");
  EXPECT_FALSE(jobFromJson(minimalJob()).modbus.has_value());
}

TEST(JobJson, SyntaxErrorsGiveLineAndColumn) {
  try {
    parseJsonText("{\n  \"tools\": [1, 2,,]\n}");
    FAIL() << "no error";
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2, column 18"), std::string::npos) << e.what();
  }
}

// A number no double holds is nlohmann's out_of_range, not a parse_error: it must come
// out as a FieldError with its place too, not escape (the fuzzer's first find: `mdhd
// check` aborted on "density": 1e400).
TEST(JobJson, NumbersTooLargeForADoubleAreErrorsWithTheirPlace) {
  for (const char* number :
       {"1e400", "-1e400",
        "777777777777777777777777777777777777777777777777777777777777777777777777777777777777777777"
        "777777777777777777777777777777777777777777777777777777777777777777777777777777777777777777"
        "777777777777777777777777777777777777777777777777777777777777777777777777777777777777777777"
        "77777777777777777777777777777777777777777e99"}) {
    const std::string text = std::string("{\n  \"options\": { \"density\": ") + number + " }\n}";
    try {
      parseJsonText(text);
      FAIL() << "no error for " << number;
    } catch (const FieldError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("line 2, column 27"), std::string::npos) << what;
      EXPECT_NE(what.find("number overflow"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace mdhd::protocol

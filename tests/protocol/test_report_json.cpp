// check::Report -> the report document: field names of the spec, joints by the
// machine's names, both error forms, and every form valid by report.schema.json.
#include <gtest/gtest.h>

#include "protocol/json_schema.h"
#include "protocol/report_json.h"
#include "sim/kinematics/presets.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;

void expectValid(const json& doc) {
  for (const auto& p : reportSchema().validate(doc))
    ADD_FAILURE() << p.path << ": " << p.message << "\n" << doc.dump(2);
}

check::Report withCollision() {
  check::Report r;
  r.status = check::Status::kCollisions;
  check::Collision c;
  c.type = check::CollisionType::kFixtureContact;
  c.line = 41;
  c.last_line = 43;
  c.block = "G0 X12 Y30 Z2";
  c.tool = 1;
  c.position = {12.0, 30.0, 2.0};
  c.joints[gcode::kX] = 12.0;
  c.joints[gcode::kC] = -0.0;
  c.depth = 0.8;
  c.part = check::ToolPartName::kHolder;
  c.fixture = 2;
  r.collisions.push_back(c);
  r.stats.moves.rapid = 3;
  r.stats.moves.arc = 2;
  r.stats.tools.push_back({1, 12.5, 300.0});
  r.mdh.directions = {1, 2, 3, 4, 5, 6};
  r.overhang.first_line = 7;
  return r;
}

TEST(ReportJson, CollisionEntryAndBlocksAsTheSpecNamesThem) {
  const kin::Machine m = kin::presets::acTrunnion();
  const json doc = reportToJson(withCollision(), &m);
  expectValid(doc);
  EXPECT_EQ(doc["status"], "collisions");
  EXPECT_TRUE(doc["error"].is_null());
  const json& c = doc["collisions"][0];
  EXPECT_EQ(c["type"], "fixture_contact");
  EXPECT_EQ(c["line"], 41);
  EXPECT_EQ(c["last_line"], 43);
  EXPECT_EQ(c["block"], "G0 X12 Y30 Z2");
  EXPECT_EQ(c["position"], json::array({12.0, 30.0, 2.0}));
  EXPECT_EQ(c["joints"], json({{"X", 12.0}, {"Y", 0.0}, {"Z", 0.0}, {"A", 0.0}, {"C", 0.0}}));
  EXPECT_EQ(c["depth"], 0.8);
  EXPECT_EQ(c["part"], "holder");
  EXPECT_EQ(c["fixture"], 2);
  EXPECT_FALSE(c.contains("axis"));
  EXPECT_EQ(doc["stats"]["moves"], 5);
  EXPECT_EQ(doc["stats"]["moves_by_kind"], json({{"rapid", 3}, {"feed", 0}, {"arc", 2}}));
  EXPECT_EQ(doc["stats"]["tools"][0],
            json({{"tool", 1}, {"cutting_time_s", 12.5}, {"removed_volume_mm3", 300.0}}));
  EXPECT_EQ(doc["mdh"]["directions"], json({{"+x", 1},
                                            {"-x", 2},
                                            {"+y", 3},
                                            {"-y", 4},
                                            {"+z", 5},
                                            {"-z", 6},
                                            {"solid", 0},
                                            {"empty", 0}}));
  EXPECT_EQ(doc["overhang"]["first_line"], 7);
}

TEST(ReportJson, JobErrorNamesTheField) {
  check::Report r;
  r.status = check::Status::kError;
  r.error = check::ReportError{"must be > 0, got -4", "tools[0].diameter", "", 0, 0, ""};
  const json doc = reportToJson(r, nullptr);
  expectValid(doc);
  EXPECT_EQ(doc["error"],
            json({{"message", "must be > 0, got -4"}, {"field", "tools[0].diameter"}}));
  EXPECT_TRUE(doc["overhang"]["first_line"].is_null());
}

TEST(ReportJson, ProgramErrorGivesThePlace) {
  check::Report r;
  r.status = check::Status::kError;
  r.error = check::ReportError{"Unknown word Q", "", "", 3, 12, "G1 X5 F100 Q"};
  json doc = reportToJson(r, nullptr);
  expectValid(doc);
  EXPECT_EQ(
      doc["error"],
      json(
          {{"message", "Unknown word Q"}, {"line", 3}, {"column", 12}, {"block", "G1 X5 F100 Q"}}));
  r.error->file = "sub";
  doc = reportToJson(r, nullptr);
  expectValid(doc);
  EXPECT_EQ(doc["error"]["file"], "sub");
}

TEST(ReportJson, WithoutAMachineJointsAreByLetter) {
  const json doc = reportToJson(withCollision(), nullptr);
  expectValid(doc);
  EXPECT_EQ(doc["collisions"][0]["joints"], json({{"X", 12.0}, {"Y", 0.0}, {"Z", 0.0}}));
}

// Every number is written as the finite number it is, however large: rounding to a
// nanometre multiplied by 1e9 first, which overflowed beyond ~1.8e299 and wrote null
// (a program's G0 X999...9 with 300 digits reported its overtravel's depth as null).
TEST(ReportJson, HugeFiniteNumbersStayNumbers) {
  check::Report r = withCollision();
  check::Collision& c = r.collisions[0];
  c.type = check::CollisionType::kAxisLimit;
  c.part = check::ToolPartName::kNone;
  c.fixture = -1;
  c.axis = "X";
  c.depth = 1e300;
  c.position = {-1e300, 2.5e299, 1e16};
  c.joints[gcode::kX] = 1e300;
  r.stats.path_length = 1.7e308;
  r.stats.cycle_time_s = 4e297;
  const json doc = reportToJson(r, nullptr);
  expectValid(doc);
  const json& e = doc["collisions"][0];
  EXPECT_EQ(e["depth"], 1e300);
  EXPECT_EQ(e["position"], json::array({-1e300, 2.5e299, 1e16}));
  EXPECT_EQ(e["joints"]["X"], 1e300);
  EXPECT_EQ(doc["stats"]["path_length"], 1.7e308);
  EXPECT_EQ(doc["stats"]["cycle_time_s"], 4e297);
  const std::string text = doc.dump();
  std::size_t nulls = 0;
  for (auto at = text.find("null"); at != std::string::npos; at = text.find("null", at + 1))
    ++nulls;
  EXPECT_EQ(nulls, 1u);  // "error": null, nothing else
  // Below 1e15 still rounded to a nanometre.
  r.collisions[0].depth = 0.1 + 0.2;
  EXPECT_EQ(reportToJson(r, nullptr)["collisions"][0]["depth"], 0.3);
}

TEST(ReportJson, SchemaRejectsAReportMissingABlock) {
  json doc = reportToJson(withCollision(), nullptr);
  doc.erase("overhang");
  const auto p = reportSchema().validate(doc);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].path, "overhang");
  doc = reportToJson(withCollision(), nullptr);
  doc["collisions"][0]["type"] = "bump";
  EXPECT_EQ(reportSchema().validate(doc).size(), 1u);
}

}  // namespace
}  // namespace mdhd::protocol

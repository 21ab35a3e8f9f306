// The tool codec: round trips, the example jobs' tools, and one test per error.
#include "protocol/tool_json.h"

#include <fstream>

#include <gtest/gtest.h>

namespace mdhd::protocol {
namespace {

using nlohmann::json;

json ballTool() {
  return json::parse(R"({ "number": 1, "shape": "ball", "diameter": 6, "flute_length": 18,
    "length": 60, "shank_diameter": 6, "corner_radius": 0, "tip_angle": 0,
    "holder": [ { "diameter": 25, "length": 30 }, { "diameter": 40, "length": 2 } ] })");
}

// The message of the FieldError that reading `j` as tools[1] throws.
std::string toolErrorOf(const json& j) {
  try {
    toolFromJson(j, "tools[1]");
  } catch (const FieldError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ToolJson, ReadsTheSpecExample) {
  const geom::Tool t = toolFromJson(ballTool(), "tools[0]");
  EXPECT_EQ(t.number, 1);
  EXPECT_EQ(t.shape, geom::ToolShape::kBall);
  EXPECT_EQ(t.diameter, 6.0);
  EXPECT_EQ(t.flute_length, 18.0);
  EXPECT_EQ(t.length, 60.0);
  EXPECT_EQ(t.shank_diameter, 6.0);
  ASSERT_EQ(t.holder.size(), 2u);
  EXPECT_EQ(t.holder[0].diameter, 25.0);
  EXPECT_EQ(t.holder[1].length, 2.0);
  EXPECT_EQ(t.holderBottom(), 28.0);
}

TEST(ToolJson, RoundTripsEveryShape) {
  const char* docs[] = {
      R"({"number": 3, "shape": "flat", "diameter": 8, "flute_length": 30, "length": 60})",
      R"({"number": 4, "shape": "bull", "diameter": 10, "flute_length": 20, "length": 70,
          "corner_radius": 1.5, "shank_diameter": 12, "holder": [{"diameter": 32, "length": 20}]})",
      R"({"number": 5, "shape": "drill", "diameter": 5, "flute_length": 40, "length": 80,
          "tip_angle": 118})",
      R"({"number": 6, "shape": "ball", "diameter": 0.3, "flute_length": 6, "length": 20,
          "shank_diameter": 0.3, "holder": [{"diameter": 10, "length": 10}]})"};
  for (const char* doc : docs) {
    const geom::Tool t = toolFromJson(json::parse(doc), "tools[0]");
    const json written = toolToJson(t);
    EXPECT_EQ(toolFromJson(written, "tools[0]"), t) << written.dump();
    EXPECT_EQ(toolToJson(toolFromJson(written, "tools[0]")), written);
  }
  const geom::Tool flat = toolFromJson(json::parse(docs[0]), "t");
  EXPECT_EQ(flat.shank_diameter, 8.0);  // defaults to the diameter
  EXPECT_TRUE(flat.holder.empty());
}

TEST(ToolJson, ReadsTheExampleJobsTools) {
  int tools = 0;
  for (const char* name : {"contour-3axis", "crash-3axis", "side-drill-ac", "donut-bc"}) {
    std::ifstream in(std::string(MDHD_SHARED_DIR) + "/examples/" + name + ".json");
    ASSERT_TRUE(in) << name;
    const json job = json::parse(in);
    const auto read = toolsFromJson(job.at("tools"));
    ASSERT_EQ(read.size(), 1u);
    EXPECT_EQ(read[0].holder.size(), 1u);
    tools += static_cast<int>(read.size());
  }
  EXPECT_EQ(tools, 4);
}

TEST(ToolJson, EveryErrorNamesItsField) {
  struct Case {
    std::function<void(json&)> edit;
    const char* error;
  };
  const Case cases[] = {
      {[](json& j) { j = json::array(); }, "tools[1]: expected an object, got an array of 0"},
      {[](json& j) { j["flute_lenght"] = 3; }, "tools[1].flute_lenght: unknown field"},
      {[](json& j) { j.erase("number"); }, "tools[1].number: missing"},
      {[](json& j) { j.erase("shape"); }, "tools[1].shape: missing"},
      {[](json& j) { j.erase("diameter"); }, "tools[1].diameter: missing"},
      {[](json& j) { j.erase("flute_length"); }, "tools[1].flute_length: missing"},
      {[](json& j) { j.erase("length"); }, "tools[1].length: missing"},
      {[](json& j) { j["number"] = 1.5; }, "tools[1].number: expected an integer"},
      {[](json& j) { j["number"] = 0; }, "tools[1].number: must be an integer >= 1"},
      {[](json& j) { j["shape"] = "taper"; },
       "tools[1].shape: expected one of flat, ball, bull, drill"},
      {[](json& j) { j["shape"] = 2; }, "tools[1].shape: expected a string"},
      {[](json& j) { j["diameter"] = "6"; }, "tools[1].diameter: expected a number"},
      {[](json& j) { j["diameter"] = 0; }, "tools[1].diameter: must be > 0"},
      {[](json& j) { j["flute_length"] = -1; }, "tools[1].flute_length: must be > 0"},
      {[](json& j) { j["length"] = 0; }, "tools[1].length: must be > 0"},
      {[](json& j) { j["shank_diameter"] = 0; }, "tools[1].shank_diameter: must be > 0"},
      {[](json& j) { j["shank_diameter"] = nullptr; },
       "tools[1].shank_diameter: expected a number"},
      {[](json& j) { j["flute_length"] = 61; }, "tools[1].flute_length: must be <= length (60)"},
      {[](json& j) { j["flute_length"] = 2; },
       "tools[1].flute_length: must be >= the height of the tip shape (3)"},
      {[](json& j) { j["corner_radius"] = 1; },
       "tools[1].corner_radius: is only used by shape bull: must be 0 or absent"},
      {[](json& j) { j["tip_angle"] = 90; },
       "tools[1].tip_angle: is only used by shape drill: must be 0 or absent"},
      {[](json& j) {
         j["shape"] = "bull";
         j.erase("corner_radius");
       },
       "tools[1].corner_radius: missing"},
      {[](json& j) {
         j["shape"] = "bull";
         j["corner_radius"] = 3.5;
       },
       "tools[1].corner_radius: must be <= diameter/2"},
      {[](json& j) {
         j["shape"] = "bull";
         j["corner_radius"] = 0;
       },
       "tools[1].corner_radius: must be > 0 for a bull"},
      {[](json& j) {
         j["shape"] = "bull";
         j["corner_radius"] = -1;
       },
       "tools[1].corner_radius: must be >= 0"},
      {[](json& j) {
         j["shape"] = "drill";
         j.erase("tip_angle");
       },
       "tools[1].tip_angle: missing"},
      {[](json& j) {
         j["shape"] = "drill";
         j["tip_angle"] = 180;
       },
       "tools[1].tip_angle: must be in (0, 180) degrees for a drill"},
      {[](json& j) {
         j["shape"] = "drill";
         j["tip_angle"] = 0;
       },
       "tools[1].tip_angle: must be in (0, 180) degrees for a drill"},
      {[](json& j) {
         j["shape"] = "drill";
         j["tip_angle"] = 30;
         j["flute_length"] = 10;
       },
       "tools[1].flute_length: must be >= the height of the tip shape (11.1962)"},
      {[](json& j) { j["holder"] = 3; },
       "tools[1].holder: expected an array of {diameter, length}"},
      {[](json& j) { j["holder"][1] = 5; }, "tools[1].holder[1]: expected an object"},
      {[](json& j) { j["holder"][1]["dia"] = 5; }, "tools[1].holder[1].dia: unknown field"},
      {[](json& j) { j["holder"][0].erase("length"); }, "tools[1].holder[0].length: missing"},
      {[](json& j) { j["holder"][1]["diameter"] = 0; }, "tools[1].holder[1].diameter: must be > 0"},
      {[](json& j) { j["holder"][0]["length"] = -2; }, "tools[1].holder[0].length: must be > 0"},
      {[](json& j) { j["holder"][0]["length"] = 70; },
       "tools[1].holder: is longer (72) than the tool length (60)"},
      {[](json& j) { j["holder"][0]["length"] = 41; },
       "tools[1].holder: reaches into the flutes: holder lengths (43) + flute_length must be <= "
       "length"},
  };
  for (const Case& c : cases) {
    json j = ballTool();
    c.edit(j);
    EXPECT_EQ(toolErrorOf(j).rfind(c.error, 0), 0u)
        << "got: " << toolErrorOf(j) << "\nwant: " << c.error;
  }
}

TEST(ToolJson, ToolListsAreArraysOfUniqueNumbers) {
  json two = json::array({ballTool(), ballTool()});
  try {
    toolsFromJson(two);
    FAIL() << "duplicate accepted";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "tools[1].number");
    EXPECT_STREQ(e.what(), "tools[1].number: tool 1 is already defined by tools[0]");
  }
  two[1]["number"] = 2;
  EXPECT_EQ(toolsFromJson(two).size(), 2u);
  EXPECT_THROW(toolsFromJson(json::object()), FieldError);
  EXPECT_TRUE(toolsFromJson(json::array()).empty());
}

}  // namespace
}  // namespace mdhd::protocol

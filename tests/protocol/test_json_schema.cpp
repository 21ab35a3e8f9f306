// The small JSON Schema validator keyword by keyword, and the project's schemas
// against the example jobs and the strict codec.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "protocol/job_json.h"
#include "protocol/json_schema.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;

std::vector<SchemaProblem> problems(const json& schema, const json& doc) {
  return JsonSchema(schema).validate(doc);
}

// The single problem a document has, as "path: message".
std::string only(const json& schema, const json& doc) {
  const auto p = problems(schema, doc);
  if (p.size() != 1) return "expected one problem, got " + std::to_string(p.size());
  return p[0].path + ": " + p[0].message;
}

json readJson(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return json::parse(text.str());
}

TEST(JsonSchema, Type) {
  const json s = {{"type", "integer"}};
  EXPECT_TRUE(problems(s, 3).empty());
  EXPECT_TRUE(problems(s, 3.0).empty());  // integral numbers are integers
  EXPECT_EQ(only(s, 3.5), "(document): expected an integer, got the number 3.5");
  EXPECT_EQ(only({{"type", json::array({"integer", "null"})}}, "x"),
            "(document): expected integer or null, got the string \"x\"");
  EXPECT_TRUE(problems({{"type", "number"}}, 2).empty());
  EXPECT_FALSE(problems({{"type", "boolean"}}, 0).empty());
}

TEST(JsonSchema, PropertiesRequiredAdditional) {
  const json s = {{"type", "object"},
                  {"properties", {{"a", {{"type", "number"}}}, {"b", {{"type", "string"}}}}},
                  {"required", {"a"}},
                  {"additionalProperties", false}};
  EXPECT_TRUE(problems(s, {{"a", 1}}).empty());
  EXPECT_EQ(only(s, json::object()), "a: missing (required)");
  EXPECT_EQ(only(s, {{"a", 1}, {"c", 2}}), "c: unknown field (known: a b)");
  EXPECT_EQ(only(s, {{"a", "x"}}), "a: expected a number, got the string \"x\"");
  const json open = {{"type", "object"}, {"additionalProperties", {{"type", "number"}}}};
  EXPECT_TRUE(problems(open, {{"X", 1}, {"Z", 2}}).empty());
  EXPECT_EQ(only(open, {{"X", true}}), "X: expected a number, got true");
  EXPECT_EQ(only({{"minProperties", 1}}, json::object()),
            "(document): must have at least 1 member(s)");
}

TEST(JsonSchema, ItemsPrefixItemsAndCounts) {
  const json s = {{"type", "array"},
                  {"prefixItems", {{{"type", "string"}}}},
                  {"items", {{"type", "number"}}},
                  {"minItems", 2},
                  {"maxItems", 3}};
  EXPECT_TRUE(problems(s, {"a", 1, 2}).empty());
  EXPECT_EQ(only(s, {"a"}), "(document): must have at least 2 item(s), got 1");
  EXPECT_EQ(only(s, {"a", 1, 2, 3}), "(document): must have at most 3 item(s), got 4");
  EXPECT_EQ(only(s, {1, 2}), "[0]: expected a string, got the number 1");
  EXPECT_EQ(only(s, {"a", "b"}), "[1]: expected a number, got the string \"b\"");
  const json nested = {{"properties", {{"v", {{"items", {{"type", "number"}}}}}}}};
  EXPECT_EQ(only(nested, {{"v", {1, "x"}}}), "v[1]: expected a number, got the string \"x\"");
}

TEST(JsonSchema, EnumAndConst) {
  EXPECT_EQ(only({{"enum", {"flat", "ball"}}}, "cone"),
            "(document): must be one of \"flat\", \"ball\", got \"cone\"");
  EXPECT_TRUE(problems({{"enum", {"flat", "ball"}}}, "ball").empty());
  EXPECT_EQ(only({{"const", 2}}, 3), "(document): must be 2");
  EXPECT_TRUE(problems({{"const", 2}}, 2).empty());
}

TEST(JsonSchema, NumericBounds) {
  EXPECT_EQ(only({{"minimum", 1}}, 0), "(document): must be >= 1, got 0");
  EXPECT_EQ(only({{"maximum", 1}}, 2), "(document): must be <= 1, got 2");
  EXPECT_EQ(only({{"exclusiveMinimum", 0}}, 0), "(document): must be > 0, got 0");
  EXPECT_EQ(only({{"exclusiveMaximum", 180}}, 180), "(document): must be < 180, got 180");
  EXPECT_TRUE(problems({{"exclusiveMinimum", 0}, {"maximum", 1}}, 1).empty());
  EXPECT_TRUE(problems({{"minimum", 1}}, "not a number").empty());  // bounds apply to numbers
}

TEST(JsonSchema, StringsMinLengthAndPattern) {
  EXPECT_EQ(only({{"minLength", 1}}, ""), "(document): must have at least 1 characters");
  EXPECT_EQ(only({{"pattern", "^[XYZ]$"}}, "Q"), "(document): must match \"^[XYZ]$\", got \"Q\"");
  EXPECT_TRUE(problems({{"pattern", "^[XYZ]$"}}, "Y").empty());
}

TEST(JsonSchema, OneOfAnyOfAllOf) {
  const json s = {{"oneOf", {{{"type", "string"}}, {{"type", "number"}, {"minimum", 0}}}}};
  EXPECT_TRUE(problems(s, "x").empty());
  EXPECT_TRUE(problems(s, 1).empty());
  EXPECT_EQ(only(s, true),
            "(document): matches none of the 2 alternatives: expected a string, got true; or "
            "expected a number, got true");
  const json both = {{"oneOf", {{{"type", "number"}}, {{"minimum", 0}}}}};
  EXPECT_EQ(only(both, 1), "(document): matches 2 alternatives where exactly one must match");
  const json any = {{"anyOf", {{{"type", "number"}}, {{"minimum", 0}}}}};
  EXPECT_TRUE(problems(any, 1).empty());
  EXPECT_TRUE(problems(any, "x").empty());  // minimum says nothing about strings
  const json anyType = {{"anyOf", {{{"type", "number"}}, {{"type", "string"}}}}};
  EXPECT_EQ(only(anyType, true),
            "(document): matches none of the 2 alternatives: expected a number, got true; or "
            "expected a string, got true");
  const json all = {{"allOf", {{{"type", "number"}}, {{"minimum", 0}}}}};
  EXPECT_EQ(only(all, -1), "(document): must be >= 0, got -1");
  // The alternative that got deepest into the document speaks for all of them.
  const json deep = {{"oneOf",
                      {{{"type", "object"},
                        {"properties", {{"box", {{"type", "number"}}}}},
                        {"required", {"box"}},
                        {"additionalProperties", false}},
                       {{"type", "object"},
                        {"properties", {{"cyl", {{"type", "number"}}}}},
                        {"required", {"cyl"}},
                        {"additionalProperties", false}}}}};
  EXPECT_EQ(only(deep, {{"box", "x"}}), "box: expected a number, got the string \"x\"");
}

TEST(JsonSchema, RefsToDefs) {
  const json s = {{"$defs", {{"pos", {{"type", "number"}, {"exclusiveMinimum", 0}}}}},
                  {"properties", {{"r", {{"$ref", "#/$defs/pos"}}}}}};
  EXPECT_TRUE(problems(s, {{"r", 1}}).empty());
  EXPECT_EQ(only(s, {{"r", 0}}), "r: must be > 0, got 0");
}

TEST(JsonSchema, RefusesWhatItCannotCheck) {
  EXPECT_THROW(JsonSchema(json{{"multipleOf", 2}}), std::invalid_argument);
  EXPECT_THROW(JsonSchema(json{{"$ref", "#/$defs/missing"}}), std::invalid_argument);
  EXPECT_THROW(JsonSchema(json{{"$ref", "other.json"}}), std::invalid_argument);
  EXPECT_THROW(JsonSchema(json{{"type", "float"}}), std::invalid_argument);
  EXPECT_THROW(JsonSchema(json{{"pattern", "("}}), std::invalid_argument);
  EXPECT_THROW(JsonSchema(json{{"properties", {{"a", {{"minimum", "x"}}}}}}),
               std::invalid_argument);
  EXPECT_THROW(JsonSchema(json(3)), std::invalid_argument);
  EXPECT_NO_THROW(JsonSchema(json{{"description", "x"}, {"default", 1}, {"title", "t"}}));
}

TEST(JsonSchema, SelfReferenceDoesNotRecurseForever) {
  const json s = {{"$defs", {{"loop", {{"$ref", "#/$defs/loop"}}}}}, {"$ref", "#/$defs/loop"}};
  const auto p = problems(s, 1);
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p[0].message, "schema nesting too deep");
}

TEST(JsonSchema, EmbeddedSchemasAreTheFilesInTheTree) {
  EXPECT_EQ(json::parse(jobSchemaText()),
            readJson(std::string(MDHD_SOURCE_DIR) + "/protocol/schemas/job.schema.json"));
  EXPECT_EQ(json::parse(reportSchemaText()),
            readJson(std::string(MDHD_SOURCE_DIR) + "/protocol/schemas/report.schema.json"));
}

TEST(JobSchema, EveryExampleJobAndMachineValidates) {
  const std::string dir = std::string(MDHD_SHARED_DIR) + "/examples/";
  for (const char* name :
       {"contour-3axis.json", "crash-3axis.json", "side-drill-ac.json", "donut-bc.json"}) {
    const auto p = jobSchema().validate(readJson(dir + name));
    EXPECT_TRUE(p.empty()) << name << ": " << p.front().path << ": " << p.front().message;
  }
  // Machine files are the schema's machine definition: inline them.
  for (const char* name :
       {"machine-3axis.json", "machine-ac-trunnion.json", "machine-bc-head-table.json"}) {
    json job = readJson(dir + "contour-3axis.json");
    job.erase("machine_file");
    job["machine"] = readJson(dir + name);
    const auto p = jobSchema().validate(job);
    EXPECT_TRUE(p.empty()) << name << ": " << p.front().path << ": " << p.front().message;
  }
}

// A complete job using every field the spec names.
json fullJob() {
  return json::parse(R"({
    "machine": {"name": "m", "joints": [
        {"name": "X", "type": "linear", "axis": [1,0,0], "limits": [-100, 100]},
        {"name": "Y", "type": "linear", "axis": [0,1,0]},
        {"name": "Z", "type": "linear", "axis": [0,0,1], "origin": [0,0,0]},
        {"name": "C", "type": "rotary", "axis": [0,0,1], "origin": [0,0,0]}],
      "tool_chain": ["X","Y","Z"], "workpiece_chain": ["C"], "home": {"Z": 100},
      "spindle_axis": [0,0,1], "rapid_feed": 10000, "max_feed": 5000},
    "tools": [{"number": 1, "shape": "bull", "diameter": 6, "flute_length": 10, "length": 40,
               "shank_diameter": 6, "corner_radius": 1, "tip_angle": 0,
               "holder": [{"diameter": 20, "length": 10}]}],
    "stock": {"box": {"min": [0,0,0], "max": [10,10,10]}},
    "fixtures": [{"box": {"min": [0,0,-5], "max": [10,10,0]}},
                 {"cylinder": {"base": [0,0,0], "axis": [0,0,1], "radius": 2, "height": 3}}],
    "work_offsets": {"G54": [0,0,0], "G59.3": [1,2,3]},
    "program": "G0 X0\n",
    "options": {"density": 5, "steps": 0, "tolerance": 0.01, "ruleset": ["CTD", "RS"],
                "seed": 3, "three_way": false, "contact_tolerance": 0.05}})");
}

TEST(JobSchema, AFullJobValidatesAndDecodes) {
  const json job = fullJob();
  const auto p = jobSchema().validate(job);
  EXPECT_TRUE(p.empty()) << p.front().path << ": " << p.front().message;
  EXPECT_NO_THROW(jobFromJson(job));
}

TEST(JobSchema, ErrorsNameTheField) {
  struct Case {
    const char* pointer;
    json value;
    const char* expected;
  };
  const Case cases[] = {
      {"/tools/0/diameter", -1, "tools[0].diameter: must be > 0, got -1"},
      {"/tools/0/shape", "cone",
       "tools[0].shape: must be one of \"flat\", \"ball\", \"bull\", \"drill\", got \"cone\""},
      {"/machine/joints/3/name", "Q",
       "machine.joints[3].name: must match \"^[XYZABCUVW]$\", got \"Q\""},
      {"/stock/box/min", json::array({0, 0}), "stock.box.min: must have at least 3 item(s), got 2"},
      {"/options/ruleset/0", "XYZ",
       "options.ruleset[0]: must be one of \"FFS\", \"FEFS\", \"FEFS-FFS\", \"CTD\", \"SPT\", "
       "\"RS\", got \"XYZ\""},
      {"/options/density", 0, "options.density: must be > 0, got 0"},
      {"/options/steps", 1.5, "options.steps: expected an integer, got the number 1.5"},
      {"/work_offsets/G60", json::array({0, 0, 0}),
       "work_offsets.G60: unknown field (known: G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3)"},
      {"/fixtures/1/cylinder/radius", 0, "fixtures[1].cylinder.radius: must be > 0, got 0"},
      {"/options/colour", "red",
       "options.colour: unknown field (known: chain_tolerance contact_tolerance density ruleset "
       "seed steps three_way tolerance two_sided)"},
  };
  for (const Case& c : cases) {
    json job = fullJob();
    job[json::json_pointer(c.pointer)] = c.value;
    const auto p = jobSchema().validate(job);
    ASSERT_FALSE(p.empty()) << c.pointer;
    EXPECT_EQ(p[0].path + ": " + p[0].message, c.expected);
  }
  json noMachine = fullJob();
  noMachine.erase("machine");
  const auto p = jobSchema().validate(noMachine);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].path, "(document)");
  EXPECT_NE(p[0].message.find("machine"), std::string::npos) << p[0].message;
}

}  // namespace
}  // namespace mdhd::protocol

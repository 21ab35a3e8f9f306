// Replays job documents through the job fuzz function (fuzz/fuzz_job_json.cpp), so CI
// without clang covers its property too: any text either fails with a FieldError or
// gives a job the schema accepts as well, whose machine and tool parts build. The
// example jobs, inline versions of them, the fuzzer's first crash (a number no double
// holds) and deterministic mutations of each.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "fuzz/fuzz_job_json.cpp"
// The folder's tests build as one unit: each fuzz function under its own name.
#define LLVMFuzzerTestOneInput fuzzModbusMapJson
#include "fuzz/fuzz_modbus_map_json.cpp"
#undef LLVMFuzzerTestOneInput
#include "tests/fuzz_replay.h"

namespace {

using mdhd::test_support::forEachMutation;
using mdhd::test_support::runFuzzFunction;

std::string readShared(const std::string& name) {
  std::ifstream in(std::string(MDHD_SHARED_DIR) + "/examples/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(JobCorpusReplay, ExamplesInlineVersionsAndMutations) {
  std::vector<std::string> corpus;
  for (const char* name : {"contour-3axis", "crash-3axis", "side-drill-ac", "donut-bc"}) {
    const std::string text = readShared(std::string(name) + ".json");
    ASSERT_FALSE(text.empty()) << name;
    corpus.push_back(text);
    // The service's form: machine and program inline.
    nlohmann::json job = nlohmann::json::parse(text);
    job["machine"] = nlohmann::json::parse(readShared(job["machine_file"].get<std::string>()));
    job["program"] = readShared(job["program_file"].get<std::string>());
    job.erase("machine_file");
    job.erase("program_file");
    corpus.push_back(job.dump(1));
  }
  corpus.push_back("{\"options\": {\"density\": 1e400}}");
  std::mt19937 random(4242);
  const std::string alphabet = "{}[]\",:0123456789.-+eE truefalsnul\n\\";
  for (const std::string& original : corpus) {
    EXPECT_EQ(runFuzzFunction(LLVMFuzzerTestOneInput, original), 0);
    forEachMutation(original, 150, alphabet, random, [](const std::string& data) {
      EXPECT_EQ(runFuzzFunction(LLVMFuzzerTestOneInput, data), 0) << data;
    });
  }
}

// The shadow's `modbus` block: the contract's example and mutations through the
// codec's round trip (fuzz/fuzz_modbus_map_json.cpp).
TEST(ModbusMapCorpusReplay, ContractExampleAndMutations) {
  const std::string example = R"({
    "host": "127.0.0.1", "port": 502, "unit_id": 1, "poll_hz": 50, "timeout_ms": 200,
    "table": "holding",
    "joints": {
      "X": { "address": 0, "type": "float32", "word_order": "abcd", "scale": 1.0 },
      "Y": { "address": 2, "type": "float32" },
      "C": { "address": 8, "type": "int32", "word_order": "cdab", "scale": 0.001 }
    },
    "tool": { "address": 10, "type": "uint16" },
    "spindle_on": { "address": 11, "type": "uint16" },
    "line": { "address": 12, "type": "uint32" },
    "feed_hold": { "coil": 0, "enabled": false }
  })";
  EXPECT_EQ(runFuzzFunction(fuzzModbusMapJson, example), 0);
  std::mt19937 random(99);
  const std::string alphabet = "{}[]\",:0123456789.-+eE truefalsnulabcdhxyz\n";
  forEachMutation(example, 600, alphabet, random, [](const std::string& data) {
    EXPECT_EQ(runFuzzFunction(fuzzModbusMapJson, data), 0) << data;
  });
}

}  // namespace

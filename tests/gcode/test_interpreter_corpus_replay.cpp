// Replays the reader's fuzz corpus (tests/data/fuzz/gcode_reader) through the
// interpreter's fuzz function (fuzz/fuzz_gcode_interpreter.cpp), so CI without clang
// covers it too: any exception other than GcodeError, a motion with a non-finite
// value, a crash or a sanitizer report fails. Also deterministic mutations.
#include <gtest/gtest.h>

// The folder's tests build as one unit: the reader's replay has its own entry point.
#define LLVMFuzzerTestOneInput fuzzGcodeInterpreter
#include "fuzz/fuzz_gcode_interpreter.cpp"
#undef LLVMFuzzerTestOneInput
#include "tests/fuzz_replay.h"

namespace {

TEST(InterpreterCorpusReplay, EveryCorpusFileAndMutations) {
  using namespace mdhd::test_support;
  const auto corpus =
      readCorpus(std::filesystem::path(MDHD_SOURCE_DIR) / "tests/data/fuzz/gcode_reader");
  ASSERT_GE(corpus.size(), 20u);
  std::mt19937 random(777);
  const std::string alphabet = "gxyzijkrpqlfsmt0123456789.-+[]#<>=()/%;*$ \n\tabcdeo";
  for (const std::string& original : corpus) {
    EXPECT_EQ(runFuzzFunction(fuzzGcodeInterpreter, original), 0);
    forEachMutation(original, 60, alphabet, random, [](const std::string& data) {
      EXPECT_EQ(runFuzzFunction(fuzzGcodeInterpreter, data), 0) << data;
    });
  }
}

}  // namespace

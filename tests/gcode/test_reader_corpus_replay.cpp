// Replays the reader's fuzz corpus (tests/data/fuzz/gcode_reader) through the
// same function the fuzzer runs, so CI without clang still covers it: any
// exception other than GcodeError, crash or sanitizer report fails the test.
// Also a few deterministic mutations of each file (truncations, byte changes).
#include <gtest/gtest.h>

#include "fuzz/fuzz_gcode_reader.cpp"
#include "tests/fuzz_replay.h"

namespace {

using mdhd::test_support::forEachMutation;
using mdhd::test_support::readCorpus;
using mdhd::test_support::runFuzzFunction;

std::vector<std::string> readerCorpus() {
  return readCorpus(std::filesystem::path(MDHD_SOURCE_DIR) / "tests/data/fuzz/gcode_reader");
}

TEST(ReaderCorpusReplay, EveryCorpusFile) {
  const auto corpus = readerCorpus();
  ASSERT_GE(corpus.size(), 20u);
  for (const std::string& text : corpus)
    EXPECT_EQ(runFuzzFunction(LLVMFuzzerTestOneInput, text), 0);
}

TEST(ReaderCorpusReplay, MutatedCorpusFiles) {
  std::mt19937 random(12345);
  const std::string alphabet = "gxyzof0123456789.-+[]#<>=()/%;*$ \n\tabcdefghijklmnopqrstuvw";
  for (const std::string& original : readerCorpus())
    forEachMutation(original, 200, alphabet, random, [](const std::string& data) {
      EXPECT_EQ(runFuzzFunction(LLVMFuzzerTestOneInput, data), 0) << data;
    });
}

}  // namespace

// Replays the reader's fuzz corpus (tests/data/fuzz/gcode_reader) through the
// interpreter's fuzz function (fuzz/fuzz_gcode_interpreter.cpp), so CI without clang
// covers it too: any exception other than GcodeError, a motion with a non-finite
// value, a crash or a sanitizer report fails. Also deterministic mutations.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

// The folder's tests build as one unit: the reader's replay has its own entry point.
#define LLVMFuzzerTestOneInput fuzzGcodeInterpreter
#include "fuzz/fuzz_gcode_interpreter.cpp"
#undef LLVMFuzzerTestOneInput

namespace {

namespace fs = std::filesystem;

std::vector<std::string> interpreterCorpus() {
  std::vector<fs::path> files;
  for (const auto& e :
       fs::directory_iterator(fs::path(MDHD_SOURCE_DIR) / "tests/data/fuzz/gcode_reader")) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<std::string> texts;
  for (const fs::path& path : files) {
    std::string data(static_cast<std::size_t>(fs::file_size(path)), '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(data.data(), static_cast<std::streamsize>(data.size()));
    texts.push_back(std::move(data));
  }
  return texts;
}

int interpret(const std::string& data) {
  return fuzzGcodeInterpreter(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
}

TEST(InterpreterCorpusReplay, EveryCorpusFileAndMutations) {
  const auto corpus = interpreterCorpus();
  ASSERT_GE(corpus.size(), 20u);
  std::mt19937 random(777);
  const std::string alphabet = "gxyzijkrpqlfsmt0123456789.-+[]#<>=()/%;*$ \n\tabcdeo";
  for (const std::string& original : corpus) {
    EXPECT_EQ(interpret(original), 0);
    for (int i = 0; i < 60 && !original.empty(); ++i) {
      std::string data = original;
      const std::size_t at = random() % data.size();
      if (i % 3 == 0)
        data.resize(at);
      else if (i % 3 == 1)
        data[at] = alphabet[random() % alphabet.size()];
      else
        data.insert(at, 1, alphabet[random() % alphabet.size()]);
      EXPECT_EQ(interpret(data), 0) << data;
    }
  }
}

}  // namespace

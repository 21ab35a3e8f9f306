// Replays the reader's fuzz corpus (tests/data/fuzz/gcode_reader) through the
// same function the fuzzer runs, so CI without clang still covers it: any
// exception other than GcodeError, crash or sanitizer report fails the test.
// Also a few deterministic mutations of each file (truncations, byte changes).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "fuzz/fuzz_gcode_reader.cpp"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> corpusFiles() {
  std::vector<fs::path> files;
  for (const auto& e :
       fs::directory_iterator(fs::path(MDHD_SOURCE_DIR) / "tests/data/fuzz/gcode_reader")) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string readFile(const fs::path& path) {
  std::string data(static_cast<std::size_t>(fs::file_size(path)), '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(data.data(), static_cast<std::streamsize>(data.size()));
  return data;
}

int run(const std::string& data) {
  return LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
}

TEST(ReaderCorpusReplay, EveryCorpusFile) {
  const auto files = corpusFiles();
  ASSERT_GE(files.size(), 20u);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    EXPECT_EQ(run(readFile(file)), 0);
  }
}

TEST(ReaderCorpusReplay, MutatedCorpusFiles) {
  std::mt19937 random(12345);
  const std::string alphabet = "gxyzof0123456789.-+[]#<>=()/%;*$ \n\tabcdefghijklmnopqrstuvw";
  for (const fs::path& file : corpusFiles()) {
    SCOPED_TRACE(file.string());
    const std::string original = readFile(file);
    for (int i = 0; i < 200 && !original.empty(); ++i) {
      std::string data = original;
      const std::size_t at = random() % data.size();
      switch (random() % 3) {
        case 0:
          data.resize(at);
          break;
        case 1:
          data[at] = alphabet[random() % alphabet.size()];
          break;
        default:
          data.insert(at, 1, alphabet[random() % alphabet.size()]);
          break;
      }
      EXPECT_EQ(run(data), 0) << data;
    }
  }
}

}  // namespace

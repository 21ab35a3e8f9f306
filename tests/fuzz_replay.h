#pragma once
// Replaying a fuzz function (fuzz/*.cpp) in the ordinary tests, so CI without clang
// covers its property too: the corpus files of a folder, and deterministic mutations
// (truncations, byte changes, insertions) of a text.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>
#include <vector>

namespace mdhd::test_support {

// The files of `dir`, sorted by name, as text.
inline std::vector<std::string> readCorpus(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<std::string> texts;
  for (const auto& path : files) {
    std::string data(static_cast<std::size_t>(std::filesystem::file_size(path)), '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(data.data(), static_cast<std::streamsize>(data.size()));
    texts.push_back(std::move(data));
  }
  return texts;
}

// Calls `use(text)` for `count` mutations of `original` (none if it is empty): in turn
// cut at, one byte replaced at and one byte inserted at a random place, the bytes
// drawn from `alphabet`.
template <class Use>
void forEachMutation(const std::string& original, int count, std::string_view alphabet,
                     std::mt19937& random, Use use) {
  for (int i = 0; i < count && !original.empty(); ++i) {
    std::string data = original;
    const std::size_t at = random() % data.size();
    if (i % 3 == 0)
      data.resize(at);
    else if (i % 3 == 1)
      data[at] = alphabet[random() % alphabet.size()];
    else
      data.insert(at, 1, alphabet[random() % alphabet.size()]);
    use(data);
  }
}

// A fuzz entry point's call on a text.
template <class Fn>
int runFuzzFunction(Fn fn, const std::string& data) {
  return fn(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
}

}  // namespace mdhd::test_support

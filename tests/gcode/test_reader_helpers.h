#pragma once
// Helpers for the reader tests: run a program text through the Reader and
// collect its blocks, or the error it raises.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/gcode/reader.h"

namespace mdhd::gcode::testing {

// External subroutines from memory: name -> file text.
inline SubroutineLoader memoryLoader(std::map<std::string, std::string> files) {
  return [files = std::move(files)](std::string_view name) -> std::unique_ptr<LineSource> {
    const auto it = files.find(std::string(name));
    if (it == files.end()) return nullptr;
    return makeStringSource(it->second);
  };
}

inline std::vector<Block> readAll(const std::string& program, ParameterStore& params,
                                  SubroutineLoader loader = {}, ReaderOptions options = {}) {
  Reader reader(makeStringSource(program), params, std::move(loader), options);
  std::vector<Block> blocks;
  Block block;
  while (reader.next(block)) blocks.push_back(block);
  return blocks;
}

inline std::vector<Block> readAll(const std::string& program, ReaderOptions options = {}) {
  ParameterStore params;
  return readAll(program, params, {}, options);
}

// The error reading `program` raises (fails the test if none).
inline GcodeError readError(const std::string& program, ReaderOptions options = {},
                            SubroutineLoader loader = {}) {
  ParameterStore params;
  try {
    readAll(program, params, std::move(loader), options);
  } catch (const GcodeError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << program;
  return GcodeError({}, "");
}

// Value of the first word `letter` of a block.
inline std::optional<double> wordValue(const Block& block, char letter) {
  for (const Word& w : block.words) {
    if (w.letter == letter) return w.value;
  }
  return std::nullopt;
}

// All values of word `letter` over the blocks, in order.
inline std::vector<double> values(const std::vector<Block>& blocks, char letter) {
  std::vector<double> out;
  for (const Block& b : blocks) {
    for (const Word& w : b.words) {
      if (w.letter == letter) out.push_back(w.value);
    }
  }
  return out;
}

}  // namespace mdhd::gcode::testing

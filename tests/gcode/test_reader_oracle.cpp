// Every program of the LinuxCNC oracle (/work/shared/gcode-oracle) through the
// reader: the ones rs274 rejects for a reader reason are rejected with the
// same message at the same line; all others read without error, and every
// motion, comment and message rs274 reported comes from a block the reader
// produced, in the same order (so sub calls, loops and ifs went the same way).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim/gcode/reader.h"

namespace mdhd::gcode {
namespace {

namespace fs = std::filesystem;

const fs::path kOracle = fs::path(MDHD_SHARED_DIR) / "gcode-oracle";

struct Rejection {
  std::string message;
  int line;
};

// Rejections that are the reader's business (the rest are the interpreter's).
const std::map<std::string, Rejection> kReaderRejections = {
    {"programs/96_reject_nested_comment.ngc", {"Nested comment found", 1}},
    {"corpus/metric_pipe.ngc",
     {"Named parameter #<_hal[plasmac.float-switch-travel]> not defined", 13}},
};

std::vector<std::string> oraclePrograms() {
  std::vector<std::string> out;
  for (const char* dir : {"programs", "corpus"}) {
    for (const auto& entry : fs::directory_iterator(kOracle / dir)) {
      if (entry.path().extension() == ".ngc") {
        out.push_back(std::string(dir) + "/" + entry.path().filename().string());
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Block> readProgram(const fs::path& path) {
  ParameterStore params;
  Reader reader(makeStreamSource(std::make_unique<std::ifstream>(path, std::ios::binary)), params,
                makeDirectoryLoader({path.parent_path().string()}));
  std::vector<Block> blocks;
  Block block;
  while (reader.next(block)) blocks.push_back(block);
  return blocks;
}

bool contains(const std::vector<std::string>& texts, const std::string& text) {
  return std::find(texts.begin(), texts.end(), text) != texts.end();
}

// Checks the oracle's records against the blocks; returns the number matched.
// Motions must come from blocks in the same order; comments and messages
// (which cutter compensation may report late) from a block of their line.
int matchRecords(const fs::path& jsonl, const std::vector<Block>& blocks, const std::string& name) {
  std::map<std::pair<std::string, int>, const Block*> by_line;
  for (const Block& b : blocks) by_line.emplace(std::make_pair(b.pos.file, b.pos.line), &b);
  std::ifstream in(jsonl);
  std::string line;
  std::size_t at = 0;
  int matched = 0;
  while (std::getline(in, line)) {
    const auto record = nlohmann::json::parse(line);
    const std::string type = record.at("type");
    if (record.at("line").is_null()) continue;
    const std::string file = record.value("file", "");
    const int number = record.at("line");
    if (type == "comment" || type == "message") {
      // Under cutter compensation rs274 queues comments and reports them with
      // the line of the block that releases them: look a few lines back.
      bool found = false;
      for (int back = 0; back <= 3 && !found; ++back) {
        const auto it = by_line.find({file, number - back});
        if (it == by_line.end()) continue;
        const auto& texts = type == "comment" ? it->second->comments : it->second->messages;
        found = contains(texts, record.at("text"));
      }
      EXPECT_TRUE(found) << name << ": " << line;
      ++matched;
      continue;
    }
    if (type != "rapid" && type != "feed" && type != "arc" && type != "probe" && type != "dwell" &&
        type != "rigid_tap") {
      continue;
    }
    while (at < blocks.size() && !(blocks[at].pos.file == file && blocks[at].pos.line == number)) {
      ++at;
    }
    if (at == blocks.size()) {
      ADD_FAILURE() << name << ": no block in order for " << line;
      return matched;
    }
    ++matched;
  }
  return matched;
}

TEST(ReaderOracle, EveryProgramReadsAsLinuxCnc) {
  const auto programs = oraclePrograms();
  ASSERT_GE(programs.size(), 38u);
  int checked_records = 0;
  for (const std::string& name : programs) {
    const fs::path path = kOracle / name;
    const auto rejection = kReaderRejections.find(name);
    if (rejection != kReaderRejections.end()) {
      try {
        readProgram(path);
        ADD_FAILURE() << name << " should be rejected";
      } catch (const GcodeError& e) {
        EXPECT_EQ(std::string(e.what()), rejection->second.message) << name;
        EXPECT_EQ(e.line(), rejection->second.line) << name;
      }
      continue;
    }
    std::vector<Block> blocks;
    try {
      blocks = readProgram(path);
    } catch (const GcodeError& e) {
      ADD_FAILURE() << name << ":" << e.line() << ":" << e.column() << ": " << e.what();
      continue;
    }
    EXPECT_FALSE(blocks.empty()) << name;
    fs::path jsonl = path;
    jsonl.replace_extension(".jsonl");
    if (fs::exists(jsonl)) checked_records += matchRecords(jsonl, blocks, name);
  }
  EXPECT_EQ(checked_records, 9896);  // all motion, comment and message records of the oracle
}

// RESULTS.tsv (file, rc, records, motions, error): every program rs274
// rejected is either one of the reader's rejections, with rs274's message,
// or one the reader accepts (the interpreter's business).
TEST(ReaderOracle, ResultsTableAgrees) {
  std::ifstream in(kOracle / "RESULTS.tsv");
  std::string row;
  std::getline(in, row);  // header
  int rows = 0;
  int reader_rejections = 0;
  while (std::getline(in, row)) {
    std::istringstream fields(row);
    std::string file, rc, records, motions, error;
    std::getline(fields, file, '\t');
    std::getline(fields, rc, '\t');
    std::getline(fields, records, '\t');
    std::getline(fields, motions, '\t');
    std::getline(fields, error);
    ++rows;
    const auto rejection = kReaderRejections.find(file);
    if (rejection != kReaderRejections.end()) {
      ++reader_rejections;
      EXPECT_EQ(rc, "2") << file;
      EXPECT_EQ(error, rejection->second.message) << file;
      continue;
    }
    EXPECT_NO_THROW(readProgram(kOracle / file)) << file << " (rs274: " << error << ")";
  }
  EXPECT_EQ(rows, 38);
  EXPECT_EQ(reader_rejections, 2);
}

TEST(ReaderOracle, OwordProgramValues) {
  // 15_oword_params_expr.ngc: the values LinuxCNC moved to (see its .jsonl).
  const auto blocks = readProgram(kOracle / "programs/15_oword_params_expr.ngc");
  std::vector<std::pair<int, double>> xs;
  for (const Block& b : blocks) {
    for (const Word& w : b.words) {
      if (w.letter == 'X') xs.emplace_back(b.pos.line, w.value);
    }
  }
  const std::vector<std::pair<int, double>> expected = {
      {10, 5.0},  {12, 5.0}, {10, 22.5}, {12, 22.5}, {20, 0.0}, {20, 10.0}, {20, 20.0},
      {24, 14.0}, {29, 1.0}, {29, 1.0},  {3, 30.0},  {4, 34.0}, {6, 30.0}};
  EXPECT_EQ(xs, expected);
}

}  // namespace
}  // namespace mdhd::gcode

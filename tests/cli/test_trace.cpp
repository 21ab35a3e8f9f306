// mdhd trace on the example jobs and on broken jobs: the joint values the spec's
// conventions give, and errors that say what and where.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "daemon/cli.h"
#include "tests/cli/example_path.h"

namespace mdhd::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct TraceRun {
  int status = 0;
  std::vector<json> motions;
  std::string err;
};

TraceRun trace(const std::string& job_path) {
  std::ostringstream out, err;
  TraceRun r;
  r.status = runTrace({job_path}, out, err);
  r.err = err.str();
  std::istringstream lines(out.str());
  for (std::string line; std::getline(lines, line);) r.motions.push_back(json::parse(line));
  return r;
}

using test_support::example;

const json* motionAtLine(const TraceRun& r, int line) {
  for (const json& m : r.motions) {
    if (m["line"] == line) return &m;
  }
  return nullptr;
}

// A scratch folder with a 3-axis job whose program is given.
class ScratchJob : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mdhd_trace_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    fs::copy_file(example("machine-3axis.json"), dir_ / "machine.json",
                  fs::copy_options::overwrite_existing);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  std::string job(const std::string& program_field) {
    return write("job.json", R"({"machine_file": "machine.json",
      "tools": [{"number": 1, "shape": "flat", "diameter": 6, "flute_length": 20, "length": 50}],
      "stock": {"box": {"min": [0, 0, -40], "max": [100, 80, 0]}},
      "work_offsets": {"G54": [10, 20, -30]}, )" +
                                 program_field + "}");
  }
  fs::path dir_;
};

TEST(Trace, ContourExample) {
  const TraceRun r = trace(example("contour-3axis.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.motions.size(), 11u);    // lines 6..16: 2 rapids, 5 feeds, 4 arcs
  const json* m = motionAtLine(r, 7);  // G1 Z-2 F300 with G43 H1 (length 50)
  ASSERT_NE(m, nullptr);
  EXPECT_EQ((*m)["type"], "feed");
  EXPECT_DOUBLE_EQ((*m)["joints"]["Z"].get<double>(), 48.0);
  EXPECT_DOUBLE_EQ((*m)["feed"].get<double>(), 300.0);
  const json* arc = motionAtLine(r, 9);  // G3 X75 Y30 I0 J5
  ASSERT_NE(arc, nullptr);
  EXPECT_EQ((*arc)["type"], "arc");
  EXPECT_EQ((*arc)["center"], json::array({70, 30}));
  EXPECT_EQ((*arc)["plane"], "XY");
  EXPECT_EQ((*arc)["turns"], 1);
}

TEST(Trace, SideDrillExampleDrivesTheTrunnion) {
  const TraceRun r = trace(example("side-drill-ac.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const json* m = motionAtLine(r, 8);  // G1 Z5 with G43 H2 (length 60) at A-90
  ASSERT_NE(m, nullptr);
  EXPECT_EQ((*m)["joints"], (json{{"X", 0}, {"Y", 15}, {"Z", 65}, {"A", -90}, {"C", 0}}));
  EXPECT_EQ((*m)["tool"], 2);
}

TEST(Trace, DonutExampleTurnsTheTable) {
  const TraceRun r = trace(example("donut-bc.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const json* m = motionAtLine(r, 12);  // G1 C360 F3600
  ASSERT_NE(m, nullptr);
  EXPECT_DOUBLE_EQ((*m)["joints"]["C"].get<double>(), 360.0);
  EXPECT_DOUBLE_EQ((*m)["joints"]["B"].get<double>(), -25.0);
  EXPECT_DOUBLE_EQ((*m)["joints"]["X"].get<double>(), -4.76237);
}

TEST_F(ScratchJob, WorkOffsetsAndToolLengthReachTheJoints) {
  const TraceRun r = trace(job(R"("program": "G21 G90 G54\nT1 M6\nG43 H1\nG0 X1 Y2 Z3\nM2\n")"));
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.motions.size(), 1u);
  EXPECT_EQ(r.motions[0]["joints"], (json{{"X", 11}, {"Y", 22}, {"Z", 23}}));
  EXPECT_EQ(r.motions[0]["line"], 4);
}

TEST_F(ScratchJob, ProgramErrorNamesLineAndColumn) {
  const TraceRun r = trace(job(R"("program": "G21 G90\nG0 X1\nG1 X2 G68 F100\nM2\n")"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.motions.size(), 1u);  // the motion before the error was delivered
  EXPECT_NE(r.err.find("line 3, column 7"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Unknown g code"), std::string::npos) << r.err;
}

TEST_F(ScratchJob, AxisTheMachineLacksIsRejected) {
  const TraceRun r = trace(job(R"("program": "G0 X1\nG0 A90\n")"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("line 2, column 4"), std::string::npos) << r.err;
}

// A machine whose Y moves along x cannot put a TCP tip at y = 1: the move is an
// error at its block's line and column, as in `mdhd check` (it was "machine: line 4").
TEST_F(ScratchJob, AMoveTheMachineCannotMakeNamesLineAndColumn) {
  json machine = json::parse(std::ifstream(dir_ / "machine.json"));
  machine["joints"][1]["axis"] = {1, 0, 0};
  std::ofstream(dir_ / "machine.json") << machine.dump();
  const TraceRun r = trace(job(R"("program": "G21 G90\nT1 M6\nG43.4 H1\n  G1 X1 Y1 F100\nM2\n")"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("program, line 4, column 3: cannot make this move"), std::string::npos)
      << r.err;
}

TEST_F(ScratchJob, ProgramFileAndExternalSubroutine) {
  write("part.ngc", "G0 X0 Y0 Z10\no<hole> call [5]\nM2\n");
  write("hole.ngc", "o<hole> sub\nG1 Z-#1 F100\no<hole> endsub\nM2\n");
  const TraceRun r = trace(job(R"("program_file": "part.ngc")"));
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.motions.size(), 2u);
  EXPECT_DOUBLE_EQ(r.motions[1]["joints"]["Z"].get<double>(), -35.0);  // -5 + G54 z -30
}

TEST_F(ScratchJob, MissingProgramFile) {
  const TraceRun r = trace(job(R"("program_file": "nowhere.ngc")"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("program_file"), std::string::npos) << r.err;
}

TEST_F(ScratchJob, BrokenJson) {
  const TraceRun r = trace(write("job.json", "{\"tools\": [\n  1,,\n]}"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("line 2, column 5"), std::string::npos) << r.err;
}

TEST_F(ScratchJob, BadFieldIsNamed) {
  const TraceRun r = trace(job(R"("program": "M2", "options": {"density": "high"})"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("options.density"), std::string::npos) << r.err;
}

TEST(Trace, Usage) {
  std::ostringstream out, err;
  EXPECT_EQ(runTrace({}, out, err), 2);
  EXPECT_NE(err.str().find("usage"), std::string::npos);
}

}  // namespace
}  // namespace mdhd::cli

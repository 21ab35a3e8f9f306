// mdhd check on broken jobs and programs (exit 2, a report whose error says what
// and where), its arguments, the report's destinations and the mesh file.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "daemon/check_runner.h"
#include "daemon/cli.h"
#include "protocol/json_schema.h"
#include "tests/cli/example_path.h"

namespace mdhd::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

using test_support::example;

// A scratch folder with a small 3-axis job (20 x 20 x 10 stock, density 4).
class CheckScratch : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mdhd_check_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
    fs::copy_file(example("machine-3axis.json"), dir_ / "machine.json",
                  fs::copy_options::overwrite_existing);
    job_ = json::parse(R"({
      "machine_file": "machine.json",
      "tools": [{"number": 1, "shape": "flat", "diameter": 4, "flute_length": 10, "length": 40,
                 "holder": [{"diameter": 20, "length": 10}]}],
      "stock": {"box": {"min": [0, 0, -10], "max": [20, 20, 0]}},
      "program_file": "p.ngc",
      "options": {"density": 4}})");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string writeJob(const std::string& program) {
    std::ofstream(dir_ / "p.ngc") << program;
    std::ofstream(dir_ / "job.json") << job_.dump(2);
    return (dir_ / "job.json").string();
  }
  int run(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    const int status = runCheck(args, out, err);
    out_ = out.str();
    err_ = err.str();
    return status;
  }
  json reportFile() {
    std::ifstream in(dir_ / "r.json");
    json r = json::parse(in);
    const auto p = protocol::reportSchema().validate(r);
    for (const auto& x : p) ADD_FAILURE() << "report schema: " << x.path << ": " << x.message;
    return r;
  }
  std::string report() const { return (dir_ / "r.json").string(); }

  fs::path dir_;
  json job_;
  std::string out_, err_;
};

constexpr const char* kPocket =
    "G21 G90 G17\nT1 M6\nG43 H1\nM3 S10000\nG0 X5 Y5 Z5\nG1 Z-2 F300\nG1 X15 F600\nG0 Z5\nM5\n"
    "M30\n";

TEST_F(CheckScratch, CleanRunReportsToStdoutWhenNoReportFile) {
  EXPECT_EQ(run({writeJob(kPocket)}), 0) << err_;
  const json r = json::parse(out_);
  EXPECT_EQ(r["status"], "clean");
  // A 4 mm slot 2 mm deep: 10 mm straight plus the two half discs at its ends.
  EXPECT_NEAR(r["stats"]["removed_volume_mm3"].get<double>(), 2 * (10 * 4 + 3.14159265 * 4), 3.0);
  EXPECT_EQ(r["stats"]["blocks"], 10);
  EXPECT_EQ(r["stats"]["moves"], 4);
}

TEST_F(CheckScratch, SchemaErrorNamesTheField) {
  job_["tools"][0]["diameter"] = -4;
  EXPECT_EQ(run({writeJob(kPocket), "--report", report()}), 2);
  EXPECT_NE(err_.find("tools[0].diameter: must be > 0"), std::string::npos) << err_;
  const json r = reportFile();
  EXPECT_EQ(r["status"], "error");
  EXPECT_EQ(r["error"]["field"], "tools[0].diameter");
  EXPECT_EQ(r["error"]["message"], "must be > 0, got -4");
}

TEST_F(CheckScratch, CodecErrorBehindTheSchemaNamesTheField) {
  // Valid by the schema, refused by the strict codec: min above max.
  job_["stock"]["box"]["min"] = {30, 0, -10};
  EXPECT_EQ(run({writeJob(kPocket), "--report", report()}), 2);
  const json r = reportFile();
  EXPECT_EQ(r["error"]["field"], "stock.box");
  EXPECT_NE(r["error"]["message"].get<std::string>().find("min must be below max"),
            std::string::npos);
}

TEST_F(CheckScratch, MissingProgramFileNamesTheField) {
  job_["program_file"] = "nowhere.ngc";
  EXPECT_EQ(run({writeJob(kPocket), "--report", report()}), 2);
  EXPECT_EQ(reportFile()["error"]["field"], "program_file");
}

TEST_F(CheckScratch, ProgramErrorGivesLineColumnAndBlock) {
  const std::string program = "G21 G90\nT1 M6\nG1 X5 F100 Q\nM30\n";
  EXPECT_EQ(run({writeJob(program), "--report", report()}), 2);
  const json r = reportFile();
  EXPECT_EQ(r["status"], "error");
  EXPECT_EQ(r["error"]["line"], 3);
  EXPECT_GT(r["error"]["column"].get<int>(), 0);
  EXPECT_EQ(r["error"]["block"], "G1 X5 F100 Q");
  EXPECT_NE(err_.find("line 3"), std::string::npos) << err_;
}

TEST_F(CheckScratch, BadJsonAndMissingFile) {
  std::ofstream(dir_ / "job.json") << "{\"tools\": [";
  EXPECT_EQ(run({(dir_ / "job.json").string(), "--report", report()}), 2);
  EXPECT_EQ(reportFile()["error"]["field"], "(document)");
  EXPECT_EQ(run({(dir_ / "absent.json").string(), "--report", report()}), 2);
  EXPECT_EQ(reportFile()["error"]["field"], "(file)");
}

TEST_F(CheckScratch, ArgumentsAreChecked) {
  EXPECT_EQ(run({}), 2);
  EXPECT_NE(err_.find("usage"), std::string::npos);
  EXPECT_EQ(run({writeJob(kPocket), "--frobnicate"}), 2);
  EXPECT_NE(err_.find("unknown option '--frobnicate'"), std::string::npos);
  EXPECT_EQ(run({writeJob(kPocket), "--report"}), 2);
  EXPECT_EQ(run({writeJob(kPocket), "other.json"}), 2);
  for (const char* bad : {"-1", "two", "", "1000", "2x"}) {
    EXPECT_EQ(run({writeJob(kPocket), "--threads", bad}), 2) << bad;
    EXPECT_NE(err_.find("--threads needs a count"), std::string::npos) << bad;
  }
  EXPECT_EQ(run({writeJob(kPocket), "--threads"}), 2);
  EXPECT_EQ(run({writeJob(kPocket), "--report", (dir_ / "no" / "dir" / "r.json").string()}), 2);
  EXPECT_NE(err_.find("cannot write the report"), std::string::npos);
}

TEST_F(CheckScratch, MeshIsAClosedBinaryStlOfTheFinalStock) {
  const std::string stl = (dir_ / "m.stl").string();
  EXPECT_EQ(run({writeJob(kPocket), "--report", report(), "--mesh", stl}), 0) << err_;
  std::ifstream in(stl, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  ASSERT_GE(bytes.size(), 84u);
  std::uint32_t n = 0;
  std::memcpy(&n, bytes.data() + 80, 4);
  ASSERT_EQ(bytes.size(), 84u + 50u * n);
  // Volume by the divergence theorem is the report's final volume: closed, outward (the
  // mesh's crossings and the heightmaps' integral differ by a fraction of a percent at
  // this coarse density).
  double volume = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) {
    float v[12];
    std::memcpy(v, bytes.data() + 84 + 50 * i, sizeof v);
    const float* a = v + 3;
    const float* b = v + 6;
    const float* c = v + 9;
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0])) /
              6.0;
  }
  const double final_volume = reportFile()["stats"]["final_volume_mm3"].get<double>();
  EXPECT_NEAR(volume, final_volume, 0.005 * final_volume);
  EXPECT_FALSE(fs::exists(stl + ".partial"));
}

TEST_F(CheckScratch, NoMeshIsWrittenForABrokenProgram) {
  const std::string stl = (dir_ / "m.stl").string();
  EXPECT_EQ(run({writeJob("G1 X5 F100 Q\n"), "--report", report(), "--mesh", stl}), 2);
  EXPECT_FALSE(fs::exists(stl));
}

TEST_F(CheckScratch, CancelStopsARunAtTheNextStep) {
  const LoadedJob loaded = loadCheckedJobFile(writeJob(kPocket));
  std::atomic<bool> cancel{false};
  int calls = 0;
  CheckControls controls;
  controls.cancel = &cancel;
  controls.progress = [&](double, std::int64_t) {
    ++calls;
    cancel = true;  // as the service's worker would, from another thread
  };
  EXPECT_THROW(runCheckJob(loaded, controls), check::Cancelled);
  EXPECT_EQ(calls, 1);
  cancel = false;
  EXPECT_EQ(runCheckJob(loaded, {}).status, check::Status::kClean);
}

// A program that runs for long without a motion (an o-word loop of assignments: up
// to a hundred million lines before the reader's limit) is stopped by the flag too,
// at its next block: a service job's cancel and run-time limit reach it.
TEST_F(CheckScratch, CancelStopsALoopWithoutMotions) {
  const LoadedJob loaded = loadCheckedJobFile(
      writeJob("#1 = 0\no100 while [#1 LT 9000000]\n#1 = [#1 + 1]\no100 endwhile\nG1 X5 F100\n"));
  std::atomic<bool> cancel{false};
  CheckControls controls;
  controls.cancel = &cancel;
  const auto start = std::chrono::steady_clock::now();
  std::thread raise([&cancel] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    cancel = true;
  });
  EXPECT_THROW(runCheckJob(loaded, controls), check::Cancelled);
  raise.join();
  // 9 M iterations take several seconds; the flag stops them within a block.
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

}  // namespace
}  // namespace mdhd::cli

// mdhd check on the shared example jobs: what examples/README.md says each
// report must show, through the command's own entry point, reports validated
// against the report schema.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "daemon/cli.h"
#include "protocol/json_schema.h"
#include "tests/cli/example_path.h"

namespace mdhd::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

struct CheckRun {
  int status = 0;
  json report;
  std::string err;
};

using test_support::example;

CheckRun check(const std::string& job, const std::vector<std::string>& extra = {}) {
  std::ostringstream out, err;
  CheckRun r;
  std::vector<std::string> args{job};
  args.insert(args.end(), extra.begin(), extra.end());
  r.status = runCheck(args, out, err);
  r.err = err.str();
  r.report = json::parse(out.str());
  const auto problems = protocol::reportSchema().validate(r.report);
  for (const auto& p : problems) ADD_FAILURE() << "report schema: " << p.path << ": " << p.message;
  return r;
}

std::int64_t notPlusZ(const json& report) {
  const json& d = report["mdh"]["directions"];
  return d["+x"].get<std::int64_t>() + d["-x"].get<std::int64_t>() + d["+y"].get<std::int64_t>() +
         d["-y"].get<std::int64_t>() + d["-z"].get<std::int64_t>();
}

TEST(CheckExamples, ContourClearsTheRingClean) {
  const CheckRun r = check(example("contour-3axis.json"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.report["status"], "clean");
  EXPECT_TRUE(r.report["error"].is_null());
  EXPECT_TRUE(r.report["collisions"].empty());
  const double removed = r.report["stats"]["removed_volume_mm3"];
  EXPECT_NEAR(removed, 1817.0, 0.01 * 1817.0);
  EXPECT_NEAR(r.report["stats"]["final_volume_mm3"].get<double>(), 100.0 * 80 * 40 - 1817.0, 20.0);
  EXPECT_EQ(notPlusZ(r.report), 0);
  EXPECT_EQ(r.report["overhang"]["area_mm2"], 0.0);
  EXPECT_EQ(r.report["stats"]["moves"], 11);
  EXPECT_EQ(r.report["stats"]["moves_by_kind"]["arc"], 4);
  // Feeds: the 7 mm plunge (Z5 to Z-2) at F300, 40+40+20+20 mm lines and four R5
  // quarter arcs at F800.
  const double cutting = (7.0 / 300 + (120.0 + 2 * kPi * 5) / 800) * 60;
  ASSERT_EQ(r.report["stats"]["tools"].size(), 1u);
  EXPECT_NEAR(r.report["stats"]["tools"][0]["cutting_time_s"].get<double>(), cutting, 1e-6);
}

TEST(CheckExamples, CrashHasTheThreeMistakesAndNothingElse) {
  const CheckRun r = check(example("crash-3axis.json"));
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.report["status"], "collisions");
  const json& c = r.report["collisions"];
  ASSERT_EQ(c.size(), 3u) << c.dump(2);
  std::set<std::pair<std::string, int>> got;
  for (const json& e : c) got.insert({e["type"].get<std::string>(), e["line"].get<int>()});
  const std::set<std::pair<std::string, int>> want{
      {"rapid_into_stock", 7}, {"holder_contact", 11}, {"shank_contact", 12}};
  EXPECT_EQ(got, want) << c.dump(2);
  for (const json& e : c) {
    EXPECT_EQ(e["tool"], 1);
    if (e["type"] == "rapid_into_stock") {
      EXPECT_EQ(e["block"], "G0 Z-1");
      // The tip enters the stock top (z 0) on the way to Z-1; 1 mm deep at the end.
      EXPECT_NEAR(e["position"][2].get<double>(), 0.0, 0.2);
      EXPECT_NEAR(e["depth"].get<double>(), 1.0, 0.2);
      EXPECT_EQ(e["joints"]["X"], 20.0);
    }
    if (e["type"] == "holder_contact") {
      // The holder starts 20 mm above the tip: it meets the top when the tip is at -20,
      // and ends 5 mm deep; the episode lasts into the retract (line 14), which starts
      // buried.
      EXPECT_EQ(e["block"], "G1 Z-25 F200");
      EXPECT_NEAR(e["position"][2].get<double>(), -20.0, 0.2);
      EXPECT_NEAR(e["depth"].get<double>(), 5.0, 0.25);
      EXPECT_EQ(e["last_line"], 14);
    }
    if (e["type"] == "shank_contact") {
      // Shank from 15 to 20 mm above the tip at Z-25: a 5 mm tall, 3 mm radius body
      // whose deepest point in the wall is 2.5 mm from its end faces.
      EXPECT_EQ(e["block"], "G1 X60 F500");
      EXPECT_NEAR(e["depth"].get<double>(), 2.5, 0.3);
      EXPECT_EQ(e["last_line"], 13);
    }
  }
}

TEST(CheckExamples, SideDrillIsAnUndercutHole) {
  const CheckRun r = check(example("side-drill-ac.json"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.report["status"], "clean");
  const double hole = kPi * 16 * 15;
  EXPECT_NEAR(r.report["stats"]["removed_volume_mm3"].get<double>(), hole, 0.01 * hole);
  const double upperHalf = kPi * 4 * 15;  // half the wall of a 4 mm radius, 15 mm hole
  EXPECT_NEAR(r.report["overhang"]["area_mm2"].get<double>(), upperHalf, 0.05 * upperHalf);
  EXPECT_GT(r.report["overhang"]["cells_not_plus_z"].get<int>(), 0);
}

TEST(CheckExamples, DonutGrooveOverhangsClean) {
  const CheckRun r = check(example("donut-bc.json"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.report["status"], "clean");
  EXPECT_TRUE(r.report["collisions"].empty());
  EXPECT_GT(r.report["overhang"]["cells_not_plus_z"].get<int>(), 0);
  EXPECT_GT(r.report["overhang"]["area_mm2"].get<double>(), 0.0);
  EXPECT_GT(r.report["stats"]["removed_volume_mm3"].get<double>(), 0.0);
}

// An example job with its options changed, written beside the test's temp files
// (its machine and program by absolute path).
std::string exampleWith(const char* name, const json& options) {
  std::ifstream in(example(name));
  json job = json::parse(in);
  const fs::path dir = fs::path(example(name)).parent_path();
  job["machine_file"] = (dir / job["machine_file"].get<std::string>()).string();
  job["program_file"] = (dir / job["program_file"].get<std::string>()).string();
  job["options"].update(options);
  const std::string tag = std::to_string(std::hash<std::string>{}(options.dump()));
  const fs::path path = fs::path(::testing::TempDir()) / ("mdhd_" + tag + "_" + name);
  std::ofstream(path) << job.dump();
  return path.string();
}

// Plain heightmaps (options.three_way false) place a surface that lies along a cell's
// direction only within a grid edge: the vertical walls of the contour are off by up to
// half a spacing on average, and where the crash's overhangs turn cells sideways the
// hole's floor is, by up to one spacing. So the real mistakes are all found, and
// anything else is shallower than a spacing: a contact tolerance of one spacing (the
// plain map's resolution) leaves exactly the three.
TEST(CheckExamples, PlainMapsHoldTheExamplesWithinOneSpacing) {
  const double h = 0.2;  // both jobs at density 5
  const CheckRun contour = check(exampleWith("contour-3axis.json", {{"three_way", false}}));
  EXPECT_EQ(contour.report["status"], "clean");
  // The ring's two walls, 2 mm tall: about 2 x (2 x (50 + 30) - 8 x 5 + 2 pi 5) mm long.
  const double walls = 2.0 * 2 * (2 * (50 + 30) - 8 * 5 + 2 * kPi * 5);
  EXPECT_NEAR(contour.report["stats"]["removed_volume_mm3"].get<double>(), 1817.0, walls * h / 2);
  const std::set<std::pair<std::string, int>> want{
      {"rapid_into_stock", 7}, {"holder_contact", 11}, {"shank_contact", 12}};
  const CheckRun crash = check(exampleWith("crash-3axis.json", {{"three_way", false}}));
  std::set<std::pair<std::string, int>> got;
  for (const json& e : crash.report["collisions"]) {
    const std::pair<std::string, int> at{e["type"].get<std::string>(), e["line"].get<int>()};
    got.insert(at);
    if (!want.contains(at)) {
      EXPECT_LT(e["depth"].get<double>(), h) << e.dump();
    }
  }
  for (const auto& w : want) EXPECT_TRUE(got.contains(w)) << w.first << " " << w.second;
  const CheckRun tolerant =
      check(exampleWith("crash-3axis.json", {{"three_way", false}, {"contact_tolerance", h}}));
  got.clear();
  for (const json& e : tolerant.report["collisions"])
    got.insert({e["type"].get<std::string>(), e["line"].get<int>()});
  EXPECT_EQ(got, want) << tolerant.report["collisions"].dump(2);
}

// Two-sided maps (options.two_sided, the default) are the same stock in fewer cells
// than one-sided ones: the same collisions at the same lines, the same volume up to
// the integration of columns on opposite sides, and no sign conflict split.
TEST(CheckExamples, TwoSidedMapsFindTheSameCollisions) {
  for (const char* name : {"crash-3axis.json", "side-drill-ac.json", "donut-bc.json"}) {
    SCOPED_TRACE(name);
    const json one = check(exampleWith(name, {{"two_sided", false}})).report;
    const json two = check(example(name)).report;
    const auto collisions = [](const json& report) {
      std::set<std::pair<std::string, int>> out;
      for (const json& e : report["collisions"])
        out.insert({e["type"].get<std::string>(), e["line"].get<int>()});
      return out;
    };
    EXPECT_EQ(collisions(two), collisions(one));
    EXPECT_EQ(two["status"], one["status"]);
    const double v1 = one["stats"]["final_volume_mm3"].get<double>();
    const double v2 = two["stats"]["final_volume_mm3"].get<double>();
    // The integrations differ only across columns on opposite sides: 1.0e-4 of the
    // donut's volume (50 grid cubes at its density 32); the bound is three times that.
    EXPECT_NEAR(v2, v1, 3e-4 * v1);
    EXPECT_EQ(two["mdh"]["splits"]["sign_conflict"].get<int>(), 0);
    EXPECT_LE(two["mdh"]["leaves"].get<int>(), one["mdh"]["leaves"].get<int>());
    std::printf(
        "%s: leaves %d -> %d, splits sign conflict %d -> 0, flipped columns %d, "
        "volume %.4f -> %.4f\n",
        name, one["mdh"]["leaves"].get<int>(), two["mdh"]["leaves"].get<int>(),
        one["mdh"]["splits"]["sign_conflict"].get<int>(),
        two["mdh"]["two_sided"]["flipped_columns"].get<int>(), v1, v2);
  }
}

// The stock is cut on several threads with bit-identical results: the report is
// the same, byte for byte, whatever the thread count (timing aside).
TEST(CheckExamples, ThreadCountChangesNothingButTime) {
  // The report and the mesh (cut and meshed on 1 and on 3 threads) are the same bytes.
  const fs::path dir = fs::path(::testing::TempDir()) / "mdhd_threads";
  fs::create_directories(dir);
  const std::string stl1 = (dir / "one.stl").string(), stl3 = (dir / "three.stl").string();
  json one = check(example("side-drill-ac.json"), {"--threads", "1", "--mesh", stl1}).report;
  json three = check(example("side-drill-ac.json"), {"--threads", "3", "--mesh", stl3}).report;
  one.erase("timing");
  three.erase("timing");
  EXPECT_EQ(one.dump(), three.dump());
  EXPECT_GT(one["mdh"]["cells"].get<std::int64_t>(), 1);
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream all;
    all << in.rdbuf();
    return all.str();
  };
  const std::string a = bytes(stl1), b = bytes(stl3);
  EXPECT_GT(a.size(), 84u + 50u * 1000u);  // header, count and a thousand triangles at least
  EXPECT_TRUE(a == b) << a.size() << " vs " << b.size() << " bytes";
  fs::remove_all(dir);
}

// Equal but for rounding: numbers within 1e-6 (relative), everything else exactly.
void expectSameReport(const json& a, const json& b, const std::string& at) {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_NEAR(x, y, 1e-9 + 1e-6 * std::abs(y)) << at;
    return;
  }
  ASSERT_EQ(a.type(), b.type()) << at;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << at;
    for (auto it = a.begin(); it != a.end(); ++it) {
      ASSERT_TRUE(b.contains(it.key())) << at << "." << it.key();
      expectSameReport(it.value(), b[it.key()], at + "." + it.key());
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << at;
    for (std::size_t i = 0; i < a.size(); ++i)
      expectSameReport(a[i], b[i], at + "[" + std::to_string(i) + "]");
  } else {
    EXPECT_EQ(a, b) << at;
  }
}

// Feed steps cut in batches (the default) or one by one give the same report:
// collisions at the same lines and depths, the same cutting times, volumes, cells
// and overhang events (check/cut_batch.h). Memory counts the rows' capacity, which
// depends on how they grew: within 1 %.
TEST(CheckExamples, BatchedCutsChangeNothingButTime) {
  for (const char* name :
       {"contour-3axis.json", "crash-3axis.json", "side-drill-ac.json", "donut-bc.json"}) {
    json batched = check(example(name)).report;
    json single = check(example(name), {"--batch", "1"}).report;
    batched.erase("timing");
    single.erase("timing");
    for (const char* memory : {"memory_bytes", "pointer_grid_percent"}) {
      const double a = batched["mdh"][memory], b = single["mdh"][memory];
      EXPECT_NEAR(a, b, 0.01 * b) << name << " " << memory;
      batched["mdh"].erase(memory);
      single["mdh"].erase(memory);
    }
    expectSameReport(batched, single, name);
  }
}

TEST(CheckExamples, BatchOptionIsChecked) {
  for (const char* bad : {"0", "257", "x", ""}) {
    std::ostringstream out, err;
    EXPECT_EQ(runCheck({example("contour-3axis.json"), "--batch", bad}, out, err), 2) << bad;
    EXPECT_NE(err.str().find("--batch needs a count"), std::string::npos) << err.str();
  }
}

}  // namespace
}  // namespace mdhd::cli

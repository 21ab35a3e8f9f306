#pragma once
// Jobs for the service tests: the shared examples with their files inlined (the
// service takes no paths), a tiny job that runs in milliseconds, a slow one that
// runs for minutes (to be cancelled), and polling a job until it settles.
#include <httplib.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

namespace mdhd::service_test {

inline std::string examplesDir() {
  return std::string(MDHD_SHARED_DIR) + "/examples/";
}

inline std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// examples/<name>.json with machine_file and program_file replaced by their content.
inline nlohmann::json inlineExample(const std::string& name) {
  nlohmann::json job = nlohmann::json::parse(readText(examplesDir() + name + ".json"));
  if (job.contains("machine_file")) {
    job["machine"] =
        nlohmann::json::parse(readText(examplesDir() + job["machine_file"].get<std::string>()));
    job.erase("machine_file");
  }
  if (job.contains("program_file")) {
    job["program"] = readText(examplesDir() + job["program_file"].get<std::string>());
    job.erase("program_file");
  }
  return job;
}

inline nlohmann::json threeAxisMachine() {
  return nlohmann::json::parse(readText(examplesDir() + "machine-3axis.json"));
}

// A slot across a small stock; `variant` moves it so jobs differ. Milliseconds.
inline nlohmann::json tinyJob(int variant = 0) {
  const int y = 2 + variant % 16;
  return {
      {"machine", threeAxisMachine()},
      {"tools",
       {{{"number", 1}, {"shape", "flat"}, {"diameter", 4}, {"flute_length", 10}, {"length", 40}}}},
      {"stock", {{"box", {{"min", {0, 0, -5}}, {"max", {20, 20, 0}}}}}},
      {"program", "G21 G90 G54\nT1 M6\nG43 H1\nM3 S9000\nG0 X-3 Y" + std::to_string(y) +
                      " Z2\nG1 Z-1 F500\nG1 X23\nG0 Z5\nM30\n"},
      {"options", {{"density", 2}}}};
}

// A zigzag of `moves` long cuts at density 10: tens of moves per second.
inline nlohmann::json slowJob(int moves = 4000) {
  nlohmann::json job = tinyJob();
  job["stock"] = {{"box", {{"min", {0, 0, -40}}, {"max", {100, 80, 0}}}}};
  std::string program = "G21 G90 G54\nT1 M6\nG43 H1\nM3 S9000\nG0 X-5 Y0 Z5\nG1 Z-3 F1000\n";
  for (int i = 0; i < moves; ++i) {
    program +=
        "G1 X" + std::to_string(i % 2 == 0 ? 105 : -5) + " Y" + std::to_string(i % 80) + "\n";
  }
  job["program"] = program + "M30\n";
  job["options"] = {{"density", 10}};
  return job;
}

inline nlohmann::json getJson(httplib::Client& cli, const std::string& path) {
  auto r = cli.Get(path.c_str());
  if (!r) return nullptr;
  return nlohmann::json::parse(r->body, nullptr, false);
}

// Polls GET /api/v1/jobs/{id} until `done`(status) holds; the last document.
template <typename Pred>
nlohmann::json waitJob(httplib::Client& cli, const std::string& id, Pred done,
                       std::chrono::milliseconds limit = std::chrono::seconds(60)) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  nlohmann::json doc;
  for (;;) {
    doc = getJson(cli, "/api/v1/jobs/" + id);
    if (doc.is_object() && doc.contains("status") && done(doc)) return doc;
    if (std::chrono::steady_clock::now() > deadline) return doc;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

inline bool settled(const nlohmann::json& doc) {
  const std::string s = doc["status"].get<std::string>();
  return s == "done" || s == "failed" || s == "cancelled";
}

inline nlohmann::json waitSettled(httplib::Client& cli, const std::string& id,
                                  std::chrono::milliseconds limit = std::chrono::seconds(60)) {
  return waitJob(cli, id, settled, limit);
}

// The report without its wall-clock timings, which differ run to run.
inline nlohmann::json withoutTiming(nlohmann::json report) {
  report.erase("timing");
  return report;
}

}  // namespace mdhd::service_test

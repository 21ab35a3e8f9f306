// bench_daemon [--seconds S] [--repeats N] [--job EXAMPLE]
// 1. wrk against `mdhd serve` while 2 simulation jobs run: requests/s and p50/p99
//    latency of GET /api/v1/jobs/{id} and GET /healthz.
// 2. The same job N times through HTTP (POST, poll until done, GET the mesh) and
//    as `mdhd check --report --mesh`, interleaved: the median ratio of wall times.
#include <httplib.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/modbus/sim_process.h"

namespace {

using Clock = std::chrono::steady_clock;
using mdhd::modbus_test::SimProcess;
namespace fs = std::filesystem;

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string examples() {
  return std::string(MDHD_SHARED_DIR) + "/examples/";
}

nlohmann::json inlineExample(const std::string& name) {
  nlohmann::json job = nlohmann::json::parse(readText(examples() + name + ".json"));
  job["machine"] =
      nlohmann::json::parse(readText(examples() + job["machine_file"].get<std::string>()));
  job["program"] = readText(examples() + job["program_file"].get<std::string>());
  job.erase("machine_file");
  job.erase("program_file");
  return job;
}

// A zigzag of long cuts at density 10: minutes of simulation, to keep workers busy.
nlohmann::json busyJob() {
  nlohmann::json job = inlineExample("contour-3axis");
  std::string program = "G21 G90 G54\nT1 M6\nG43 H1\nM3 S9000\nG0 X-5 Y0 Z5\nG1 Z-3 F1000\n";
  for (int i = 0; i < 4000; ++i) {
    program +=
        "G1 X" + std::to_string(i % 2 == 0 ? 105 : -5) + " Y" + std::to_string(i % 80) + "\n";
  }
  job["program"] = program + "M30\n";
  job["options"] = {{"density", 10}};
  return job;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Runs a command, returns its stdout (popen: wrk prints its summary there).
std::string capture(const std::string& command) {
  std::string out;
  std::FILE* p = popen(command.c_str(), "r");
  if (p == nullptr) return out;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

// "1.23ms" -> 1.23, "850.00us" -> 0.85, "1.01s" -> 1010.
double millis(const std::string& text) {
  std::size_t used = 0;
  const double v = std::stod(text, &used);
  const std::string unit = text.substr(used);
  if (unit == "us") return v / 1000.0;
  if (unit == "s") return v * 1000.0;
  return v;
}

struct WrkResult {
  double rps = 0.0;
  double p50 = 0.0;
  double p99 = 0.0;
  long errors = 0;
};

WrkResult runWrk(int port, const std::string& path, double seconds) {
  const std::string command = "wrk -t2 -c8 -d" + std::to_string(static_cast<int>(seconds)) +
                              "s --latency http://127.0.0.1:" + std::to_string(port) + path +
                              " 2>&1";
  const std::string out = capture(command);
  WrkResult r;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string first;
    std::string second;
    words >> first >> second;
    if (first == "50%") r.p50 = millis(second);
    if (first == "99%") r.p99 = millis(second);
    if (first == "Requests/sec:") r.rps = std::stod(second);
    if (first == "Non-2xx") {
      std::string count = line.substr(line.rfind(' ') + 1);
      r.errors += std::stol(count);
    }
  }
  if (r.rps == 0.0) std::cerr << "bench_daemon: wrk said:\n" << out;
  return r;
}

std::vector<std::string> serveArgs(const fs::path& dir, int workers) {
  fs::create_directories(dir);
  return {MDHD_BIN,
          "serve",
          "--port",
          "0",
          "--data-dir",
          (dir / "data").string(),
          "--log-file",
          (dir / "log.jsonl").string(),
          "--workers",
          std::to_string(workers),
          "--shutdown-grace-seconds",
          "0",
          "--max-job-seconds",
          "600"};
}

class Daemon {
 public:
  Daemon(const fs::path& dir, int workers) : process_(serveArgs(dir, workers)) {
    const std::string line = process_.readLine(std::chrono::seconds(20));
    if (line.find("listening on") == std::string::npos) {
      throw std::runtime_error("mdhd serve did not start: " + process_.errors());
    }
    port_ = std::stoi(line.substr(line.rfind(':') + 1));
  }
  ~Daemon() { process_.stop(SIGTERM, std::chrono::seconds(10)); }
  int port() const { return port_; }
  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", port_);
    c->set_tcp_nodelay(true);
    c->set_read_timeout(60, 0);
    return c;
  }

 private:
  SimProcess process_;
  int port_ = 0;
};

std::string post(httplib::Client& cli, const nlohmann::json& job) {
  auto r = cli.Post("/api/v1/jobs", job.dump(), "application/json");
  if (!r || r->status != 202) throw std::runtime_error("POST failed");
  return nlohmann::json::parse(r->body)["id"];
}

nlohmann::json status(httplib::Client& cli, const std::string& id) {
  auto r = cli.Get(("/api/v1/jobs/" + id).c_str());
  return r ? nlohmann::json::parse(r->body) : nlohmann::json();
}

struct HttpTimes {
  double report = 0.0;  // POST .. the report in hand
  double mesh = 0.0;    // POST .. the mesh saved
  double engine = 0.0;  // the job's own total (report timing.total_ms) on the worker
};

HttpTimes httpJob(httplib::Client& cli, const nlohmann::json& job, const fs::path& meshPath) {
  const Clock::time_point t0 = Clock::now();
  const std::string id = post(cli, job);
  nlohmann::json doc;
  for (;;) {
    doc = status(cli, id);
    const std::string s = doc["status"];
    if (s == "done" || s == "failed" || s == "cancelled") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  HttpTimes t;
  t.report = std::chrono::duration<double>(Clock::now() - t0).count();
  t.engine = doc["report"]["timing"]["total_ms"].get<double>() / 1000.0;
  {
    std::ofstream out(meshPath, std::ios::binary);
    cli.Get(("/api/v1/jobs/" + id + "/mesh").c_str(), [&](const char* data, std::size_t n) {
      out.write(data, static_cast<std::streamsize>(n));
      return true;
    });
  }
  t.mesh = std::chrono::duration<double>(Clock::now() - t0).count();
  cli.Delete(("/api/v1/jobs/" + id).c_str());
  return t;
}

double checkJob(const std::string& jobFile, const fs::path& dir) {
  const Clock::time_point t0 = Clock::now();
  SimProcess check({MDHD_BIN, "check", jobFile, "--report", (dir / "check.json").string(), "--mesh",
                    (dir / "check.stl").string()});
  check.stop(0, std::chrono::seconds(600));
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 5;
  int repeats = 5;
  std::string example = "contour-3axis";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--seconds") seconds = std::max(1.0, std::stod(argv[i + 1]));
    if (a == "--repeats") repeats = std::max(1, std::stoi(argv[i + 1]));
    if (a == "--job") example = argv[i + 1];
  }
  const fs::path dir =
      fs::temp_directory_path() / ("mdhd-bench-daemon-" + std::to_string(getpid()));
  fs::create_directories(dir);
  try {
    {
      Daemon daemon(dir / "load", 2);
      auto cli = daemon.client();
      const std::string a = post(*cli, busyJob());
      const std::string b = post(*cli, busyJob());
      while (status(*cli, a)["status"] != "running" || status(*cli, b)["status"] != "running") {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      std::printf("wrk -t2 -c8 -d%ds, 2 simulation jobs running on 2 workers:\n",
                  static_cast<int>(seconds));
      for (const std::string& path : {"/api/v1/jobs/" + a, std::string("/healthz")}) {
        const WrkResult r = runWrk(daemon.port(), path, seconds);
        std::printf("  GET %-48s %9.0f req/s  p50 %7.3f ms  p99 %7.3f ms  non-2xx %ld\n",
                    path.c_str(), r.rps, r.p50, r.p99, r.errors);
      }
      const double progress = status(*cli, a)["progress"];
      std::printf("  (the jobs were still running: progress %.3f)\n", progress);
    }
    const nlohmann::json job = inlineExample(example);
    const std::string jobFile = examples() + example + ".json";
    Daemon daemon(dir / "overhead", 1);
    auto cli = daemon.client();
    checkJob(jobFile, dir);  // warm-up of both paths (page cache, allocator), not counted
    httpJob(*cli, job, dir / "http.stl");
    std::vector<double> ratioReport;
    std::vector<double> ratioMesh;
    std::vector<double> checkTimes;
    std::vector<double> httpTimes;
    std::vector<double> beyondEngine;
    std::vector<double> beyondEngineRatio;
    for (int i = 0; i < repeats; ++i) {
      const double check = checkJob(jobFile, dir);
      const HttpTimes t = httpJob(*cli, job, dir / "http.stl");
      checkTimes.push_back(check);
      httpTimes.push_back(t.mesh);
      ratioReport.push_back(t.report / check);
      ratioMesh.push_back(t.mesh / check);
      beyondEngine.push_back(t.report - t.engine);
      beyondEngineRatio.push_back(t.report / t.engine);
    }
    std::printf("%s, %d runs each, interleaved (medians):\n", example.c_str(), repeats);
    std::printf("  mdhd check --report --mesh (process)    %8.3f s\n", median(checkTimes));
    std::printf("  HTTP: POST .. mesh downloaded            %8.3f s\n", median(httpTimes));
    std::printf("  overhead of HTTP: POST .. report %+6.1f %%, POST .. mesh downloaded %+6.1f %%\n",
                (median(ratioReport) - 1.0) * 100.0, (median(ratioMesh) - 1.0) * 100.0);
    std::printf(
        "  HTTP path beyond the job's own run (POST, queue, store, polls): %.1f ms = %+.1f %%\n",
        median(beyondEngine) * 1000.0, (median(beyondEngineRatio) - 1.0) * 100.0);
    const bool same =
        readText((dir / "check.stl").string()) == readText((dir / "http.stl").string());
    std::printf("  STL of both paths byte-equal: %s\n", same ? "yes" : "NO");
    fs::remove_all(dir);
    return same ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "bench_daemon: " << e.what() << "\n";
    fs::remove_all(dir);
    return 1;
  }
}

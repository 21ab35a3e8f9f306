// The real `mdhd serve` binary killed with SIGKILL at several moments (right after
// a 202, while jobs are being posted, while a job runs) and stopped with SIGTERM,
// then started again on the same data folder: every job acknowledged with 202 is
// there and finishes, with the report and mesh the same job gives when nothing
// goes wrong.
#include <gtest/gtest.h>

#include <atomic>
#include <iostream>
#include <mutex>
#include <thread>

#include "../modbus/sim_process.h"
#include "daemon/service_job.h"
#include "job_helpers.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

using modbus_test::SimProcess;
using namespace std::chrono_literals;

// A job of several hundred milliseconds: long enough to be killed while it runs.
nlohmann::json mediumJob() {
  nlohmann::json job = tinyJob();
  job["stock"] = {{"box", {{"min", {0, 0, -6}}, {"max", {60, 40, 0}}}}};
  std::string program = "G21 G90 G54\nT1 M6\nG43 H1\nM3 S9000\nG0 X-5 Y0 Z5\nG1 Z-3 F1000\n";
  for (int i = 0; i < 30; ++i) {
    program += "G1 X" + std::to_string(i % 2 == 0 ? 65 : -5) + " Y" + std::to_string(i) + "\n";
  }
  job["program"] = program + "M30\n";
  job["options"] = {{"density", 5}};
  return job;
}

class Daemon {
 public:
  explicit Daemon(const std::filesystem::path& dir)
      : process_({MDHD_BIN, "serve", "--port", "0", "--data-dir", (dir / "data").string(),
                  "--log-file", (dir / "log.jsonl").string(), "--workers", "1",
                  "--shutdown-grace-seconds", "0", "--max-interruptions", "100",
                  "--no-example-machines"}) {
    const std::string line = process_.readLine(20s);
    const auto colon = line.rfind(':');
    if (line.find("listening on") == std::string::npos || colon == std::string::npos) {
      throw std::runtime_error("mdhd serve did not start: '" + line + "'");
    }
    port_ = std::stoi(line.substr(colon + 1));
  }
  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", port_);
    c->set_tcp_nodelay(true);
    c->set_read_timeout(10, 0);
    return c;
  }
  int stop(int sig) { return process_.stop(sig, 10s); }

 private:
  SimProcess process_;
  int port_ = 0;
};

// The jobs posted and the ones acknowledged with 202, by the variant they are.
struct Ledger {
  std::mutex mutex;
  std::map<std::string, int> accepted;  // id -> variant (-1: the medium job)
  void add(const std::string& id, int variant) {
    const std::lock_guard<std::mutex> lock(mutex);
    accepted[id] = variant;
  }
};

nlohmann::json jobOf(int variant) {
  return variant < 0 ? mediumJob() : tinyJob(variant);
}

// Posts up to 8 jobs, until the daemon stops answering or `stop` is raised.
void postUntilGone(const Daemon& daemon, Ledger& ledger, std::atomic<bool>& stop, int first) {
  auto cli = daemon.client();
  for (int i = first; !stop && i < first + 8; ++i) {
    const int variant = i % 4 == 0 ? -1 : i % 8;
    auto r = cli->Post("/api/v1/jobs", jobOf(variant).dump(), "application/json");
    if (!r) return;
    if (r->status == 202) ledger.add(nlohmann::json::parse(r->body)["id"], variant);
    std::this_thread::sleep_for(10ms);
  }
}

// Posts a job (expecting 202), notes it in the ledger, returns its id.
std::string postJob(httplib::Client& cli, Ledger& ledger, int variant) {
  auto r = cli.Post("/api/v1/jobs", jobOf(variant).dump(), "application/json");
  if (!r || r->status != 202) throw std::runtime_error("POST was not accepted");
  const std::string id = nlohmann::json::parse(r->body)["id"];
  ledger.add(id, variant);
  return id;
}

bool isRunning(const nlohmann::json& d) {
  return d["status"] == "running";
}

TEST(Durability, KilledAtAnyMomentNoAcceptedJobIsLost) {
  TempDir dir;
  Ledger ledger;
  int posted = 0;

  {  // A job running when the daemon dies runs again after the restart.
    Daemon daemon(dir.path());
    auto cli = daemon.client();
    const std::string id = postJob(*cli, ledger, -1);
    for (int v = 0; v < 3; ++v) postJob(*cli, ledger, v);
    ASSERT_EQ(waitJob(*cli, id, isRunning)["status"], "running");
    EXPECT_EQ(daemon.stop(SIGKILL), 128 + SIGKILL);
  }
  {  // Killed right after a 202.
    Daemon daemon(dir.path());
    auto cli = daemon.client();
    postJob(*cli, ledger, 5);
    daemon.stop(SIGKILL);
  }
  for (auto delay : {20ms, 120ms, 400ms, 900ms}) {  // killed while jobs are posted and run
    Daemon daemon(dir.path());
    std::atomic<bool> stop{false};
    std::thread poster(postUntilGone, std::cref(daemon), std::ref(ledger), std::ref(stop), posted);
    std::this_thread::sleep_for(delay);
    daemon.stop(SIGKILL);
    stop = true;
    poster.join();
    posted += 8;
  }
  {  // SIGTERM: the running job is stopped and queued again; exit status 0.
    Daemon daemon(dir.path());
    auto cli = daemon.client();
    const std::string id = postJob(*cli, ledger, -1);
    ASSERT_EQ(waitJob(*cli, id, isRunning, 120s)["status"], "running");
    EXPECT_EQ(daemon.stop(SIGTERM), 0);
  }

  // What each variant gives when nothing goes wrong, run in this process.
  std::map<int, std::pair<nlohmann::json, std::string>> expected;
  for (const auto& [id, variant] : ledger.accepted) {
    if (expected.count(variant)) continue;
    const auto mesh = dir.path() / ("expected-" + std::to_string(variant + 1) + ".stl");
    const service::JobOutcome out = service::runServiceJob(jobOf(variant).dump(), mesh, {});
    expected[variant] = {nlohmann::json::parse(out.report), readText(mesh.string())};
  }

  Daemon daemon(dir.path());
  auto cli = daemon.client();
  EXPECT_GE(ledger.accepted.size(), 8u);
  int reran = 0;
  for (const auto& [id, variant] : ledger.accepted) {
    const nlohmann::json doc = waitSettled(*cli, id, 120s);
    ASSERT_EQ(doc["status"], "done") << id << ": " << doc.dump().substr(0, 300);
    EXPECT_EQ(withoutTiming(doc["report"]), withoutTiming(expected[variant].first)) << id;
    auto mesh = cli->Get(("/api/v1/jobs/" + id + "/mesh").c_str());
    ASSERT_TRUE(mesh);
    ASSERT_EQ(mesh->status, 200);
    EXPECT_TRUE(mesh->body == expected[variant].second) << id;
    reran += doc["attempts"].get<int>() > 1;
  }
  std::cout << ledger.accepted.size() << " jobs acknowledged, " << reran << " ran again\n";
  EXPECT_GE(reran, 2);  // the killed running job and the one stopped by SIGTERM
  // Nothing is left half-way, acknowledged or not.
  for (std::string cursor;;) {
    const nlohmann::json page =
        getJson(*cli, "/api/v1/jobs?limit=100" + (cursor.empty() ? "" : "&cursor=" + cursor));
    for (const auto& j : page["jobs"])
      EXPECT_EQ(waitSettled(*cli, j["id"], 120s)["status"], "done");
    if (page["next_cursor"].is_null()) break;
    cursor = page["next_cursor"];
  }
  EXPECT_EQ(daemon.stop(SIGTERM), 0);
}

}  // namespace
}  // namespace mdhd::service_test

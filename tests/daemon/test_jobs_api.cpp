// /api/v1/jobs and /api/v1/machines through HTTP against the real service on a
// loopback port: the example jobs end to end (report and STL equal to `mdhd check`'s),
// machines by name, every refusal with its status, paging, cancel, limits.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <sstream>

#include "daemon/cli.h"
#include "daemon/http_errors.h"
#include "daemon/service_job.h"
#include "job_helpers.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

struct Posted {
  int status = 0;
  nlohmann::json body;
  std::string location;
};

Posted postJob(httplib::Client& cli, const nlohmann::json& job) {
  auto r = cli.Post("/api/v1/jobs", job.dump(), "application/json");
  if (!r) return {};
  return {r->status, nlohmann::json::parse(r->body, nullptr, false),
          r->get_header_value("Location")};
}

// What `mdhd check` writes for an example: the report document and the STL bytes.
struct CheckOutput {
  nlohmann::json report;
  std::string stl;
};

CheckOutput runCheckCommand(const std::string& example, const std::filesystem::path& dir) {
  const std::string report = (dir / (example + ".report.json")).string();
  const std::string mesh = (dir / (example + ".stl")).string();
  std::ostringstream out;
  std::ostringstream err;
  cli::runCheck({examplesDir() + example + ".json", "--report", report, "--mesh", mesh}, out, err);
  return {nlohmann::json::parse(readText(report)), readText(mesh)};
}

class JobsApi : public ::testing::Test {
 protected:
  service::ServiceConfig config() { return testConfig(dir_.path()); }
  TempDir dir_;
};

TEST_F(JobsApi, ExampleJobsGiveWhatCheckGives) {
  service::ServiceConfig c = config();
  c.workers = 2;
  RunningService svc(c);
  auto cli = svc.client();
  const std::vector<std::string> examples = {"contour-3axis", "crash-3axis", "side-drill-ac",
                                             "donut-bc"};
  std::map<std::string, std::string> ids;
  for (const std::string& name : examples) {
    const Posted p = postJob(*cli, inlineExample(name));
    ASSERT_EQ(p.status, 202) << name << ": " << p.body.dump();
    EXPECT_EQ(p.body["status"], "queued");
    EXPECT_EQ(p.location, "/api/v1/jobs/" + p.body["id"].get<std::string>());
    ids[name] = p.body["id"];
  }
  for (const std::string& name : examples) {
    const nlohmann::json doc = waitSettled(*cli, ids[name]);
    ASSERT_EQ(doc["status"], "done") << name << ": " << doc.dump().substr(0, 500);
    EXPECT_EQ(doc["progress"], 1.0);
    const CheckOutput expected = runCheckCommand(name, dir_.path());
    EXPECT_EQ(withoutTiming(doc["report"]), withoutTiming(expected.report)) << name;
    auto mesh = cli->Get(("/api/v1/jobs/" + ids[name] + "/mesh").c_str());
    ASSERT_TRUE(mesh);
    EXPECT_EQ(mesh->status, 200);
    EXPECT_EQ(mesh->get_header_value("Content-Type"), "model/stl");
    EXPECT_TRUE(mesh->body == expected.stl) << name << ": STL differs (" << mesh->body.size()
                                            << " vs " << expected.stl.size() << " bytes)";
  }
  // The examples' own verdicts, as the README of the examples states them.
  EXPECT_EQ(waitSettled(*cli, ids["crash-3axis"])["report"]["status"], "collisions");
  EXPECT_EQ(waitSettled(*cli, ids["contour-3axis"])["report"]["status"], "clean");
  // The listing carries no reports, but each finished job's verdict: its report's status
  // and number of collisions.
  const nlohmann::json list = getJson(*cli, "/api/v1/jobs");
  ASSERT_EQ(list["jobs"].size(), examples.size());
  for (const auto& j : list["jobs"]) {
    EXPECT_FALSE(j.contains("report"));
    const nlohmann::json report = waitSettled(*cli, j["id"])["report"];
    EXPECT_EQ(j["verdict"]["status"], report["status"]) << j.dump();
    EXPECT_EQ(j["verdict"]["collisions"], report["collisions"].size()) << j.dump();
  }
  const nlohmann::json crash = waitSettled(*cli, ids["crash-3axis"]);
  EXPECT_EQ(crash["verdict"], nlohmann::json({{"status", "collisions"}, {"collisions", 3}}));
}

TEST_F(JobsApi, MachinesByNameAndTheRegistry) {
  RunningService svc(config());
  auto cli = svc.client();
  // The presets are there on a fresh data folder.
  const nlohmann::json list = getJson(*cli, "/api/v1/machines");
  std::set<std::string> names;
  for (const auto& m : list["machines"]) names.insert(m["name"].get<std::string>());
  for (const char* preset : {"3axis-mill", "ac-trunnion", "bc-head-table", "nutating-b45"}) {
    EXPECT_TRUE(names.count(preset)) << preset;
  }
  // Register the example's AC trunnion under a name and run side-drill-ac by name.
  const std::string machine = readText(examplesDir() + "machine-ac-trunnion.json");
  auto put = cli->Put("/api/v1/machines/shop-ac", machine, "application/json");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 201);
  put = cli->Put("/api/v1/machines/shop-ac", machine, "application/json");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 200);
  EXPECT_EQ(getJson(*cli, "/api/v1/machines/shop-ac"), nlohmann::json::parse(machine));

  nlohmann::json job = inlineExample("side-drill-ac");
  const nlohmann::json inlineDoc = job;
  job["machine"] = "shop-ac";
  const Posted byName = postJob(*cli, job);
  ASSERT_EQ(byName.status, 202) << byName.body.dump();
  const Posted inlined = postJob(*cli, inlineDoc);
  ASSERT_EQ(inlined.status, 202);
  const nlohmann::json a = waitSettled(*cli, byName.body["id"]);
  const nlohmann::json b = waitSettled(*cli, inlined.body["id"]);
  ASSERT_EQ(a["status"], "done");
  EXPECT_EQ(a["machine"], "shop-ac");
  EXPECT_EQ(withoutTiming(a["report"]), withoutTiming(b["report"]));

  // Bad machines and names.
  auto bad = cli->Put("/api/v1/machines/x", R"({"joints": []})", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_FALSE(body(bad)["error"]["field"].get<std::string>().empty());
  auto badName = cli->Put("/api/v1/machines/..hidden", machine, "application/json");
  ASSERT_TRUE(badName);
  EXPECT_EQ(badName->status, 400);
  EXPECT_EQ(body(badName)["error"]["code"], "bad_name");
  job["machine"] = "no-such-machine";
  const Posted unknown = postJob(*cli, job);
  EXPECT_EQ(unknown.status, 400);
  EXPECT_EQ(unknown.body["error"]["code"], "unknown_machine");
  EXPECT_EQ(unknown.body["error"]["field"], "machine");

  auto del = cli->Delete("/api/v1/machines/shop-ac");
  ASSERT_TRUE(del);
  EXPECT_EQ(del->status, 204);
  auto gone = cli->Get("/api/v1/machines/shop-ac");
  ASSERT_TRUE(gone);
  EXPECT_EQ(gone->status, 404);
  // The accepted job kept its copy.
  EXPECT_EQ(getJson(*cli, "/api/v1/jobs/" + byName.body["id"].get<std::string>())["status"],
            "done");
  // ... which the job's document shows: the machine inlined, the program as sent.
  const nlohmann::json doc =
      getJson(*cli, "/api/v1/jobs/" + byName.body["id"].get<std::string>() + "/job");
  EXPECT_EQ(doc["machine"], nlohmann::json::parse(machine));
  EXPECT_EQ(doc["program"], inlineDoc["program"]);
  EXPECT_EQ(doc["tools"], inlineDoc["tools"]);
}

TEST_F(JobsApi, BadDocumentsAreRefusedWithWhatAndWhere) {
  service::ServiceConfig c = config();
  c.max_body_bytes = 64 * 1024;
  c.max_program_bytes = 2000;
  RunningService svc(c);
  auto cli = svc.client();

  auto malformed = cli->Post("/api/v1/jobs", "{\"tools\": [", "application/json");
  ASSERT_TRUE(malformed);
  EXPECT_EQ(malformed->status, 400);
  EXPECT_EQ(body(malformed)["error"]["code"], "bad_json");

  // A number no double holds is the JSON's fault too, with its place (it escaped the
  // parser's syntax errors once).
  auto overflow =
      cli->Post("/api/v1/jobs", "{\"options\": {\"density\": 1e400}}", "application/json");
  ASSERT_TRUE(overflow);
  EXPECT_EQ(overflow->status, 400);
  EXPECT_EQ(body(overflow)["error"]["code"], "bad_json");
  EXPECT_NE(body(overflow)["error"]["message"].get<std::string>().find("line 1, column 25"),
            std::string::npos)
      << body(overflow);

  nlohmann::json job = tinyJob();
  job["tools"][0]["diameter"] = -4;
  Posted p = postJob(*cli, job);
  EXPECT_EQ(p.status, 400);
  EXPECT_EQ(p.body["error"]["code"], "bad_field");
  EXPECT_EQ(p.body["error"]["field"], "tools[0].diameter");

  job = tinyJob();
  job["stock"]["box"]["colour"] = "red";
  p = postJob(*cli, job);
  EXPECT_EQ(p.status, 400);
  EXPECT_NE(p.body["error"]["field"].get<std::string>().find("stock.box"), std::string::npos)
      << p.body.dump();

  job = tinyJob();
  job.erase("program");
  job["program_file"] = "/etc/passwd";
  p = postJob(*cli, job);
  EXPECT_EQ(p.status, 400);
  EXPECT_EQ(p.body["error"]["field"], "program_file");

  job = tinyJob();
  job["program"] = "G21 G90\nG1 X10 F100\nG1 X20 Q\n";
  p = postJob(*cli, job);
  EXPECT_EQ(p.status, 422) << p.body.dump();
  EXPECT_EQ(p.body["error"]["code"], "program_error");
  EXPECT_EQ(p.body["error"]["line"], 3);
  EXPECT_GE(p.body["error"]["column"].get<int>(), 1);
  EXPECT_EQ(p.body["error"]["block"], "G1 X20 Q");

  job = tinyJob();
  job["program"] = "G21\nG0 B10\n";  // the 3-axis machine has no B
  p = postJob(*cli, job);
  EXPECT_EQ(p.status, 422);
  EXPECT_EQ(p.body["error"]["line"], 2);

  job = tinyJob();
  job["program"] = "G21\nO<nope> call\nM30\n";  // a subroutine file: never looked up
  p = postJob(*cli, job);
  EXPECT_EQ(p.status, 422);
  EXPECT_EQ(p.body["error"]["line"], 2);

  job = tinyJob();
  job["program"] = std::string(3000, '(') + "\n";
  p = postJob(*cli, job);
  EXPECT_EQ(p.status, 413);
  EXPECT_EQ(p.body["error"]["code"], "program_too_large");

  job = tinyJob();
  job["comment"] = std::string(70 * 1024, 'x');
  p = postJob(*cli, job);
  EXPECT_EQ(p.status, 413);

  for (const char* text : {"[]", "42", "null", "\"job\""}) {
    auto r = cli->Post("/api/v1/jobs", text, "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << text;
  }
  auto list = getJson(*cli, "/api/v1/jobs");
  EXPECT_TRUE(list["jobs"].empty());  // nothing refused was stored
}

// The dry interpretation of a POST stops at its budget and takes the job on what it
// read: a canned cycle of 110 million pecks (one block) or a loop of 9 million
// assignments must not hold the request for minutes. An error the budget did not
// reach is the run's to report; one it reached is still a 422.
TEST(AcceptJob, DryInterpretationStopsAtItsBudget) {
  const auto noMachines = [](const std::string&) -> std::optional<nlohmann::json> {
    return std::nullopt;
  };
  for (const char* program :
       {"G21 G90 G54\nT1 M6\nM3 S9000\nG0 X10 Y10 Z5\nG83 X10 Y10 Z-10 R1 Q0.0000001 "
        "F100\nG80\nM30\n",
        "#1 = 0\no100 while [#1 LT 9000000]\n#1 = [#1 + 1]\no100 endwhile\nG1 X5 F100 Q\nM30\n"}) {
    nlohmann::json job = tinyJob();
    job["program"] = program;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NO_THROW(service::acceptJob(job, 1u << 20, noMachines, std::chrono::milliseconds(200)))
        << program;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2)) << program;
  }
  nlohmann::json bad = tinyJob();
  bad["program"] = "G21 G90\nG1 X5 F100 Q\nM30\n";
  try {
    service::acceptJob(bad, 1u << 20, noMachines, std::chrono::milliseconds(200));
    FAIL() << "no error";
  } catch (const service::HttpError& e) {
    EXPECT_EQ(e.status(), 422);
  }
}

// A stock the engine cannot hold at the job's density is refused when it is posted,
// at options.density, not accepted and failed when it runs.
TEST(AcceptJob, AStockTooFineForTheEngineIsRefusedAtTheDensity) {
  const auto noMachines = [](const std::string&) -> std::optional<nlohmann::json> {
    return std::nullopt;
  };
  nlohmann::json job = tinyJob();
  job["stock"] = {{"box", {{"min", {0, 0, -5}}, {"max", {1500, 20, 0}}}}};
  job["options"] = {{"density", 1000}};  // 1.5 million grid cubes along x
  try {
    service::acceptJob(job, 1u << 20, noMachines, std::chrono::milliseconds(200));
    FAIL() << "accepted";
  } catch (const service::HttpError& e) {
    EXPECT_EQ(e.status(), 400);
    EXPECT_EQ(e.extra().value("field", ""), "options.density");
    EXPECT_NE(std::string(e.what()).find("lower the density"), std::string::npos) << e.what();
  }
  job["options"] = {{"density", 10}};
  EXPECT_NO_THROW(service::acceptJob(job, 1u << 20, noMachines, std::chrono::milliseconds(200)));
}

TEST_F(JobsApi, UnknownIdsAre404AndPathsNeverReachFiles) {
  RunningService svc(config());
  auto cli = svc.client();
  for (const char* path :
       {"/api/v1/jobs/00000000000000000000000000000000", "/api/v1/jobs/not-an-id",
        "/api/v1/jobs/00000000000000000000000000000000/mesh",
        "/api/v1/jobs/00000000000000000000000000000000/job",
        "/api/v1/jobs/..%2F..%2Fmdhd.sqlite3/mesh", "/api/v1/jobs/%2e%2e/mesh",
        "/api/v1/machines/nope", "/api/v1/machines/..%2Fx"}) {
    auto r = cli->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path << " " << r->body;
    EXPECT_TRUE(body(r)["error"].is_object()) << path;
  }
  auto del = cli->Delete("/api/v1/jobs/00000000000000000000000000000000");
  ASSERT_TRUE(del);
  EXPECT_EQ(del->status, 404);
}

TEST_F(JobsApi, FullQueueIs429AndHealthzSaysSo) {
  service::ServiceConfig c = config();
  c.queue_limit = 2;
  c.shutdown_grace_seconds = 0;
  RunningService svc(c);
  auto cli = svc.client();
  const Posted running = postJob(*cli, slowJob());
  ASSERT_EQ(running.status, 202);
  waitJob(*cli, running.body["id"],
          [](const nlohmann::json& d) { return d["status"] == "running"; });
  ASSERT_EQ(postJob(*cli, tinyJob(1)).status, 202);
  ASSERT_EQ(postJob(*cli, tinyJob(2)).status, 202);
  auto full = cli->Post("/api/v1/jobs", tinyJob(3).dump(), "application/json");
  ASSERT_TRUE(full);
  EXPECT_EQ(full->status, 429);
  EXPECT_EQ(body(full)["error"]["code"], "queue_full");
  EXPECT_FALSE(full->get_header_value("Retry-After").empty());
  auto health = cli->Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 503);
  EXPECT_EQ(health->get_header_value("Retry-After"), "5");
  // Cancelling the running job lets the queue drain and the service take work again.
  auto cancel = cli->Delete(("/api/v1/jobs/" + running.body["id"].get<std::string>()).c_str());
  ASSERT_TRUE(cancel);
  EXPECT_EQ(cancel->status, 200);
  const auto list = getJson(*cli, "/api/v1/jobs");
  for (const auto& j : list["jobs"]) waitSettled(*cli, j["id"]);
  health = cli->Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(postJob(*cli, tinyJob(4)).status, 202);
}

TEST_F(JobsApi, CancellingARunningJobIsPrompt) {
  RunningService svc(config());
  auto cli = svc.client();
  const Posted p = postJob(*cli, slowJob());
  ASSERT_EQ(p.status, 202);
  const std::string id = p.body["id"];
  const nlohmann::json running = waitJob(*cli, id, [](const nlohmann::json& d) {
    return d["status"] == "running" && d["progress"].get<double>() > 0.0;
  });
  ASSERT_EQ(running["status"], "running");
  EXPECT_LT(running["progress"].get<double>(), 1.0);
  const auto t0 = std::chrono::steady_clock::now();
  auto r = cli->Delete(("/api/v1/jobs/" + id).c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(body(r)["status"], "cancelled");
  EXPECT_LT(seconds, 1.0);
  const nlohmann::json after = getJson(*cli, "/api/v1/jobs/" + id);
  EXPECT_EQ(after["status"], "cancelled");
  EXPECT_FALSE(after.contains("report"));
  auto mesh = cli->Get(("/api/v1/jobs/" + id + "/mesh").c_str());
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->status, 409);
  // A cancelled job is deleted by a second DELETE.
  r = cli->Delete(("/api/v1/jobs/" + id).c_str());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 204);
  EXPECT_EQ(cli->Get(("/api/v1/jobs/" + id).c_str())->status, 404);
}

TEST_F(JobsApi, CancellingAQueuedJobAndDeletingAFinishedOne) {
  service::ServiceConfig c = config();
  c.shutdown_grace_seconds = 0;
  RunningService svc(c);
  auto cli = svc.client();
  const Posted slow = postJob(*cli, slowJob());
  const Posted waiting = postJob(*cli, tinyJob());
  ASSERT_EQ(waiting.status, 202);
  auto r = cli->Delete(("/api/v1/jobs/" + waiting.body["id"].get<std::string>()).c_str());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(body(r)["status"], "cancelled");
  ASSERT_TRUE(cli->Delete(("/api/v1/jobs/" + slow.body["id"].get<std::string>()).c_str()));

  const Posted done = postJob(*cli, tinyJob());
  const std::string id = done.body["id"];
  ASSERT_EQ(waitSettled(*cli, id)["status"], "done");
  const auto meshFile = std::filesystem::path(c.data_dir) / "meshes" / (id + ".stl");
  EXPECT_TRUE(std::filesystem::exists(meshFile));
  r = cli->Delete(("/api/v1/jobs/" + id).c_str());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 204);
  EXPECT_FALSE(std::filesystem::exists(meshFile));
  EXPECT_EQ(cli->Get(("/api/v1/jobs/" + id).c_str())->status, 404);
}

TEST_F(JobsApi, ListingIsNewestFirstAndPaged) {
  RunningService svc(config());
  auto cli = svc.client();
  std::vector<std::string> ids;
  for (int i = 0; i < 5; ++i) ids.push_back(postJob(*cli, tinyJob(i)).body["id"]);
  std::vector<std::string> seen;
  std::string cursor;
  for (int page = 0; page < 5; ++page) {
    const nlohmann::json doc =
        getJson(*cli, "/api/v1/jobs?limit=2" + (cursor.empty() ? "" : "&cursor=" + cursor));
    ASSERT_TRUE(doc["jobs"].size() <= 2u);
    for (const auto& j : doc["jobs"]) {
      seen.push_back(j["id"]);
      EXPECT_FALSE(j.contains("report"));
    }
    if (doc["next_cursor"].is_null()) break;
    cursor = doc["next_cursor"];
  }
  EXPECT_EQ(seen, std::vector<std::string>(ids.rbegin(), ids.rend()));
  auto bad = cli->Get("/api/v1/jobs?limit=0");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  bad = cli->Get("/api/v1/jobs?cursor=abc");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
}

TEST_F(JobsApi, AJobOverTheTimeLimitFails) {
  service::ServiceConfig c = config();
  c.max_job_seconds = 0.3;
  RunningService svc(c);
  auto cli = svc.client();
  const Posted p = postJob(*cli, slowJob());
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json doc = waitSettled(*cli, p.body["id"], std::chrono::seconds(20));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  ASSERT_EQ(doc["status"], "failed");
  EXPECT_EQ(doc["report"]["status"], "error");
  EXPECT_NE(doc["report"]["error"]["message"].get<std::string>().find("limit"), std::string::npos);
}

TEST_F(JobsApi, TokensGuardTheJobRoutes) {
  service::ServiceConfig c = config();
  c.tokens = {"job-token-0123456789"};
  RunningService svc(c);
  auto anonymous = svc.client();
  auto r = anonymous->Post("/api/v1/jobs", tinyJob().dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  auto wrong = svc.client("job-token-wrong-0000");
  r = wrong->Get("/api/v1/jobs");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  auto right = svc.client("job-token-0123456789");
  const Posted p = postJob(*right, tinyJob());
  EXPECT_EQ(p.status, 202);
  EXPECT_EQ(waitSettled(*right, p.body["id"])["status"], "done");
}

TEST_F(JobsApi, MetricsCountJobsAndRequests) {
  RunningService svc(config());
  auto cli = svc.client();
  const Posted p = postJob(*cli, tinyJob());
  waitSettled(*cli, p.body["id"]);
  // The worker counts the job just after it commits the result: poll briefly.
  auto r = cli->Get("/metrics");
  for (int i = 0; i < 100 && r &&
                  r->body.find("mdhd_jobs_finished_total{outcome=\"done\"} 1") == std::string::npos;
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    r = cli->Get("/metrics");
  }
  ASSERT_TRUE(r);
  EXPECT_NE(r->body.find("mdhd_jobs_finished_total{outcome=\"done\"} 1"), std::string::npos)
      << r->body;
  EXPECT_NE(r->body.find("mdhd_http_request_duration_seconds_bucket{le=\"0.0005\"}"),
            std::string::npos);
  EXPECT_NE(r->body.find("mdhd_job_duration_seconds_count 1"), std::string::npos);
  EXPECT_NE(r->body.find("mdhd_http_requests_total{route=\"/api/v1/jobs\",method=\"POST\","
                         "status=\"202\"} 1"),
            std::string::npos);
  EXPECT_NE(r->body.find("mdhd_jobs_queued 0"), std::string::npos);
  EXPECT_NE(r->body.find("mdhd_simulated_moves_total 4"), std::string::npos);
}

}  // namespace
}  // namespace mdhd::service_test

namespace mdhd::service_test {
namespace {

// Every "$ref" in `j` names a schema that `doc` has.
void expectRefsResolve(const nlohmann::json& j, const nlohmann::json& doc) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      if (key == "$ref" && value.is_string()) {
        const std::string ref = value;
        const std::string prefix = "#/components/schemas/";
        ASSERT_EQ(ref.rfind(prefix, 0), 0u) << ref;
        EXPECT_TRUE(doc["components"]["schemas"].contains(ref.substr(prefix.size()))) << ref;
      } else {
        expectRefsResolve(value, doc);
      }
    }
  } else if (j.is_array()) {
    for (const auto& value : j) expectRefsResolve(value, doc);
  }
}

TEST(OpenApi, DescribesEveryRouteOfTheContract) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()));
  auto r = svc.client()->Get("/openapi.json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const nlohmann::json doc = body(r);
  const std::vector<std::pair<std::string, std::string>> contract = {
      {"/api/v1/jobs", "post"},
      {"/api/v1/jobs", "get"},
      {"/api/v1/jobs/{id}", "get"},
      {"/api/v1/jobs/{id}", "delete"},
      {"/api/v1/jobs/{id}/mesh", "get"},
      {"/api/v1/machines", "get"},
      {"/api/v1/machines/{name}", "put"},
      {"/api/v1/machines/{name}", "get"},
      {"/api/v1/machines/{name}", "delete"},
      {"/api/v1/shadows", "post"},
      {"/api/v1/shadows/{id}", "get"},
      {"/api/v1/shadows/{id}", "delete"},
      {"/api/v1/shadows/{id}/events", "get"},
      {"/api/v1/shadows/{id}/mesh", "get"},
      {"/healthz", "get"},
      {"/metrics", "get"},
      {"/openapi.json", "get"}};
  for (const auto& [path, method] : contract) {
    ASSERT_TRUE(doc["paths"].contains(path)) << path;
    const nlohmann::json& op = doc["paths"][path];
    ASSERT_TRUE(op.contains(method)) << method << " " << path;
    EXPECT_TRUE(op[method].contains("responses")) << method << " " << path;
  }
  for (const char* schema : {"Job", "Job_machine", "Report", "Error", "JobStatus"}) {
    EXPECT_TRUE(doc["components"]["schemas"].contains(schema)) << schema;
  }
  expectRefsResolve(doc, doc);
}

}  // namespace
}  // namespace mdhd::service_test

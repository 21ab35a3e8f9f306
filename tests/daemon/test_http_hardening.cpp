// The HTTP front against hostile or sloppy clients, over raw sockets where a
// library client would not send the request: one service per port, chunked and
// mis-framed bodies refused before they are read (and before the token check
// reads them), slow headers cut off, case-insensitive media type and auth
// scheme, and meshes bounded in size and cancellable while they are written.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "../modbus/sim_process.h"
#include "daemon/http_errors.h"
#include "job_helpers.h"
#include "raw_socket.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

using HardClock = std::chrono::steady_clock;

const std::string kHardToken = "0123456789abcdef-hardening-token";

double secondsSince(HardClock::time_point t0) {
  return std::chrono::duration<double>(HardClock::now() - t0).count();
}

void sendAll(int fd, const std::string& data) {
  std::size_t off = 0;
  while (off < data.size()) {
    const ssize_t n = send(fd, data.data() + off, data.size() - off, MSG_NOSIGNAL);
    if (n <= 0) return;  // the server may have answered and closed already
    off += static_cast<std::size_t>(n);
  }
}

struct RawReply {
  int status = 0;  // 0: no reply
  std::string text;
  double seconds = 0;   // from the start of sending to the whole reply
  bool closed = false;  // the server closed the connection after the reply
};

// Reads one reply (headers and Content-Length body) within `limit` seconds.
RawReply readReply(int fd, HardClock::time_point t0, double limit) {
  RawReply r;
  std::size_t need = std::string::npos;
  for (;;) {
    const double left = limit - secondsSince(t0);
    pollfd p{fd, POLLIN, 0};
    if (left <= 0 || poll(&p, 1, static_cast<int>(left * 1000)) <= 0) break;
    char buf[4096];
    const ssize_t n = recv(fd, buf, sizeof buf, 0);
    if (n <= 0) {
      r.closed = true;
      break;
    }
    r.text.append(buf, static_cast<std::size_t>(n));
    const std::size_t end = r.text.find("\r\n\r\n");
    if (end != std::string::npos && need == std::string::npos) {
      const std::size_t cl = r.text.find("Content-Length: ");
      need =
          end + 4 + (cl != std::string::npos && cl < end ? std::stoul(r.text.substr(cl + 16)) : 0);
    }
    if (need != std::string::npos && r.text.size() >= need) break;
  }
  r.seconds = secondsSince(t0);
  if (r.text.rfind("HTTP/1.1 ", 0) == 0) r.status = std::atoi(r.text.c_str() + 9);
  return r;
}

// Sends `request` (head and whatever body) on a fresh connection and reads the
// reply; then whether the server closes the connection within a second.
RawReply rawExchange(int port, const std::string& request, double limit = 8.0) {
  const int fd = connectLoopback(port);
  const HardClock::time_point t0 = HardClock::now();
  sendAll(fd, request);
  RawReply r = readReply(fd, t0, limit);
  if (!r.closed && r.status != 0) {
    pollfd p{fd, POLLIN, 0};
    char c;
    r.closed = poll(&p, 1, 1000) > 0 && recv(fd, &c, 1, 0) <= 0;
  }
  close(fd);
  return r;
}

nlohmann::json replyJson(const RawReply& r) {
  const std::size_t end = r.text.find("\r\n\r\n");
  if (end == std::string::npos) return nullptr;
  return nlohmann::json::parse(r.text.substr(end + 4), nullptr, false);
}

void addJsonEcho(service::HttpService& http) {
  http.route({"POST", "/api/v1/hard-echo", {{"summary", "echo"}}},
             [](const httplib::Request& req, httplib::Response& res) {
               service::sendJson(res, 200, service::parseJsonBody(req));
             });
}

std::string chunked(const std::string& data, std::size_t piece) {
  std::string out;
  char size[32];
  for (std::size_t i = 0; i < data.size(); i += piece) {
    const std::size_t n = std::min(piece, data.size() - i);
    std::snprintf(size, sizeof size, "%zx\r\n", n);
    out += size + data.substr(i, n) + "\r\n";
  }
  return out + "0\r\n\r\n";
}

TEST(HttpHardening, ASecondServiceOnTheSamePortIsRefused) {
  TempDir dir;
  RunningService first(testConfig(dir.path()));
  TempDir other;
  service::ServiceConfig c = testConfig(other.path());
  c.port = first->port();
  service::Service second(c);
  try {
    second.start();
    FAIL() << "a second service listens on port " << c.port;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
  }
  // The real binary says so and exits 2 (timeout's 124 would mean it kept serving).
  const std::string command =
      std::string("timeout 20 ") + MDHD_BIN + " serve --port " + std::to_string(c.port) +
      " --data-dir " + (other.path() / "bin-data").string() + " --log-file " +
      (other.path() / "bin.log").string() + " >" + (other.path() / "out").string() + " 2>" +
      (other.path() / "err").string();
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(readText((other.path() / "err").string()).find("cannot listen"), std::string::npos);
}

TEST(HttpHardening, ChunkedBodiesAreBoundedByTheLimit) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.max_body_bytes = 4096;
  RunningService svc(c, false);
  addJsonEcho(svc->http());
  svc.start();
  const std::string head =
      "POST /api/v1/hard-echo HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
      "Transfer-Encoding: chunked\r\n\r\n";
  // Under the limit: read and served like any body.
  const RawReply small = rawExchange(svc->port(), head + chunked(R"({"k": [1, 2, 3]})", 5));
  EXPECT_EQ(small.status, 200) << small.text;
  EXPECT_EQ(replyJson(small)["k"][2], 3);
  // 1 MiB of spaces before a valid document: 413, and the connection is closed.
  const std::string big = std::string(1 << 20, ' ') + R"({"k": 1})";
  const RawReply over = rawExchange(svc->port(), head + chunked(big, 65536));
  EXPECT_EQ(over.status, 413) << over.text.substr(0, 300);
  EXPECT_EQ(replyJson(over)["error"]["code"], "body_too_large");
  EXPECT_TRUE(over.closed);
  // The service still serves.
  EXPECT_EQ(rawExchange(svc->port(), head + chunked(R"({"again": true})", 64)).status, 200);
}

TEST(HttpHardening, BodiesAreRefusedBeforeTheyAreRead) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.tokens = {kHardToken};
  c.max_body_bytes = 4096;
  RunningService svc(c, false);
  addJsonEcho(svc->http());
  svc.start();
  const int port = svc->port();
  const std::string post = "POST /api/v1/hard-echo HTTP/1.1\r\nHost: x\r\n";
  const std::string auth = "Authorization: Bearer " + kHardToken + "\r\n";
  // No token: 401 at once, though the announced body never comes.
  RawReply r = rawExchange(port, post + "Content-Length: 4000\r\n\r\n{");
  EXPECT_EQ(r.status, 401) << r.text;
  EXPECT_LT(r.seconds, 3.0);
  EXPECT_TRUE(r.closed);
  // A chunked body without a token is not read either.
  r = rawExchange(port, post + "Transfer-Encoding: chunked\r\n\r\n10\r\n");
  EXPECT_EQ(r.status, 401) << r.text;
  EXPECT_LT(r.seconds, 3.0);
  // Over the limit by Content-Length: 413 at once, not after the read timeout.
  r = rawExchange(port, post + auth + "Content-Length: 99999999\r\n\r\n{}");
  EXPECT_EQ(r.status, 413) << r.text;
  EXPECT_EQ(replyJson(r)["error"]["code"], "body_too_large");
  EXPECT_LT(r.seconds, 3.0);
  // A negative or malformed Content-Length: 400 at once.
  for (const char* length : {"-5", "12abc", "1e3", " "}) {
    r = rawExchange(port, post + auth + "Content-Length: " + length + "\r\n\r\n{}");
    EXPECT_EQ(r.status, 400) << length << "\n" << r.text;
    EXPECT_LT(r.seconds, 3.0) << length;
  }
  r = rawExchange(port, post + auth + "Content-Length: 2\r\nContent-Length: 3\r\n\r\n{}");
  EXPECT_EQ(r.status, 400) << r.text;
  // Compressed bodies would be inflated past any limit: refused.
  r = rawExchange(port, post + auth + "Content-Encoding: gzip\r\nContent-Length: 2\r\n\r\n{}");
  EXPECT_EQ(r.status, 415) << r.text;
  // A fitting body with the token is served, and the connection is kept.
  r = rawExchange(
      port,
      post + auth + "Content-Type: application/json\r\nContent-Length: 9\r\n\r\n{\"a\": 1}\n");
  EXPECT_EQ(r.status, 200) << r.text;
  EXPECT_FALSE(r.closed);
}

TEST(HttpHardening, MethodsWithoutABodyGet405AndNoFramingMeansNoBody) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()), false);
  addJsonEcho(svc->http());
  svc.start();
  const int port = svc->port();
  for (const char* method : {"PUT", "PATCH", "DELETE", "GET", "OPTIONS"}) {
    const RawReply r =
        rawExchange(port, std::string(method) + " /api/v1/hard-echo HTTP/1.1\r\nHost: x\r\n\r\n");
    EXPECT_EQ(r.status, 405) << method << "\n" << r.text;
    EXPECT_NE(r.text.find("Allow: POST"), std::string::npos) << method;
    EXPECT_EQ(replyJson(r)["error"]["code"], "method_not_allowed");
    EXPECT_LT(r.seconds, 3.0) << method;
  }
  // POST without Content-Length or Transfer-Encoding has an empty body (RFC 9112),
  // not one read until the connection ends.
  const RawReply empty = rawExchange(port, "POST /api/v1/hard-echo HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_EQ(empty.status, 400) << empty.text;
  EXPECT_EQ(replyJson(empty)["error"]["code"], "bad_json");
  EXPECT_LT(empty.seconds, 3.0);
  // Unknown paths with a body: 404 without reading it.
  const RawReply nowhere =
      rawExchange(port, "POST /nowhere HTTP/1.1\r\nHost: x\r\nContent-Length: 100000\r\n\r\n");
  EXPECT_EQ(nowhere.status, 404) << nowhere.text;
  EXPECT_LT(nowhere.seconds, 3.0);
}

TEST(HttpHardening, MediaTypeAndBearerSchemeAreCaseInsensitive) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.tokens = {kHardToken};
  RunningService svc(c, false);
  addJsonEcho(svc->http());
  svc.start();
  for (const char* scheme : {"Bearer", "bearer", "BEARER", "bEaReR  "}) {
    auto cli = svc.client();
    auto r =
        cli->Post("/api/v1/hard-echo", {{"Authorization", std::string(scheme) + " " + kHardToken}},
                  R"({"x": 1})", "APPLICATION/JSON; Charset=UTF-8");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << scheme << " " << r->body;
  }
  auto cli = svc.client(kHardToken);
  auto notJson = cli->Post("/api/v1/hard-echo", R"({"x": 1})", "application/jsonp");
  ASSERT_TRUE(notJson);
  EXPECT_EQ(notJson->status, 415);
  auto noScheme = svc.client()->Get("/metrics", {{"Authorization", "Bearer"}});
  ASSERT_TRUE(noScheme);
  EXPECT_EQ(noScheme->status, 401);
}

TEST(HttpHardening, SlowHeadersAreCutOffAtTheHeadDeadline) {
  TempDir dir;
  service::JsonLog log((dir.path() / "log.jsonl").string());
  service::Metrics metrics;
  service::HttpSettings settings;
  settings.port = 0;
  settings.threads = 2;
  settings.head_timeout = std::chrono::milliseconds(1500);
  service::HttpService http(settings, log, metrics);
  http.route({"GET", "/ping", {{"summary", "ping"}}, false},
             [](const httplib::Request&, httplib::Response& res) {
               service::sendJson(res, 200, {{"pong", true}});
             });
  http.start();
  // Two clients (as many as there are threads) send one header line every 300 ms:
  // each read is quick, the head never ends.
  std::atomic<bool> stop{false};
  std::vector<int> slow;
  for (int i = 0; i < 2; ++i) {
    slow.push_back(connectLoopback(http.port()));
    sendAll(slow.back(), "GET /ping HTTP/1.1\r\nHost: x\r\n");
  }
  std::thread drip([&] {
    while (!stop) {
      for (int fd : slow) sendAll(fd, "X-Slow: 1\r\n");
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const RawReply r = rawExchange(http.port(), "GET /ping HTTP/1.1\r\nHost: x\r\n\r\n", 6.0);
  stop = true;
  drip.join();
  for (int fd : slow) close(fd);
  EXPECT_EQ(r.status, 200) << r.text;
  EXPECT_LT(r.seconds, 4.0);  // the slow ones were dropped after 1.5 s
  // A head over its size limit is refused too (not buffered whole).
  const RawReply huge = rawExchange(
      http.port(), "GET /ping HTTP/1.1\r\nX-Big: " + std::string(200000, 'a') + "\r\n\r\n", 6.0);
  EXPECT_NE(huge.status, 200);
  http.stop();
}

// A job whose final stock is a large mesh: 600 x 600 mm at density 10 is about
// 490 MB of STL, meshed in well under a second; `side` scales it.
nlohmann::json bigStockJob(int side) {
  nlohmann::json job = tinyJob();
  for (auto& joint : job["machine"]["joints"]) {
    if (joint.contains("limits")) joint["limits"] = {-100000, 100000};
  }
  job["stock"] = {{"box", {{"min", {0, 0, -40}}, {"max", {side, side, 0}}}}};
  job["options"] = {{"density", 10}};
  return job;
}

std::string postHard(httplib::Client& cli, const nlohmann::json& job) {
  auto r = cli.Post("/api/v1/jobs", job.dump(), "application/json");
  if (!r || r->status != 202) return "";
  return nlohmann::json::parse(r->body)["id"];
}

bool noMeshFiles(const std::filesystem::path& meshes) {
  for (const auto& entry : std::filesystem::directory_iterator(meshes)) {
    ADD_FAILURE() << "left behind: " << entry.path();
    return false;
  }
  return true;
}

TEST(HttpHardening, AMeshOverTheCapIsNotWritten) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.max_mesh_mb = 1;
  RunningService svc(c);
  auto cli = svc.client();
  const std::string id = postHard(*cli, bigStockJob(100));
  ASSERT_FALSE(id.empty());
  const nlohmann::json doc = waitSettled(*cli, id);
  EXPECT_EQ(doc["status"], "done");
  EXPECT_EQ(doc["report"]["status"], "clean");
  EXPECT_FALSE(doc.contains("mesh"));
  EXPECT_EQ(doc["mesh_error"]["code"], "mesh_too_large");
  auto mesh = cli->Get(("/api/v1/jobs/" + id + "/mesh").c_str());
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->status, 409);
  EXPECT_EQ(body(mesh)["error"]["code"], "mesh_too_large");
  EXPECT_TRUE(noMeshFiles(std::filesystem::path(c.data_dir) / "meshes"));
  // A small one still gets its mesh.
  const std::string small = postHard(*cli, tinyJob());
  EXPECT_EQ(waitSettled(*cli, small)["status"], "done");
  auto ok = cli->Get(("/api/v1/jobs/" + small + "/mesh").c_str());
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  EXPECT_FALSE(getJson(*cli, "/api/v1/jobs/" + small).contains("mesh_error"));
}

TEST(HttpHardening, CancelStopsMeshing) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.max_mesh_mb = 100000;
  RunningService svc(c);
  auto cli = svc.client();
  // About 3 GB of STL and several seconds of meshing; the cut itself is one move.
  const std::string id = postHard(*cli, bigStockJob(1500));
  ASSERT_FALSE(id.empty());
  const std::filesystem::path partial =
      std::filesystem::path(c.data_dir) / "meshes" / (id + ".stl.partial");
  const HardClock::time_point t0 = HardClock::now();
  while (!std::filesystem::exists(partial) && secondsSince(t0) < 30) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(std::filesystem::exists(partial)) << "the mesh phase never started";
  const HardClock::time_point t1 = HardClock::now();
  auto r = cli->Delete(("/api/v1/jobs/" + id).c_str());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(body(r)["status"], "cancelled");
  EXPECT_LT(secondsSince(t1), 1.0);
  EXPECT_EQ(getJson(*cli, "/api/v1/jobs/" + id)["status"], "cancelled");
  EXPECT_TRUE(noMeshFiles(std::filesystem::path(c.data_dir) / "meshes"));
}

TEST(HttpHardening, AFailedMeshWriteLeavesTheStoreWhole) {
  // The real binary with a file size limit of 4 MiB (dash counts 512-byte blocks)
  // and SIGXFSZ ignored: writes past it fail with EFBIG, as on a full disk.
  TempDir dir;
  const std::string command = "ulimit -f 8192; trap '' XFSZ; exec " + std::string(MDHD_BIN) +
                              " serve --port 0 " + "--data-dir " + (dir.path() / "data").string() +
                              " --log-file " + (dir.path() / "log.jsonl").string() +
                              " --workers 1 --no-example-machines";
  modbus_test::SimProcess daemon({"/bin/sh", "-c", command});
  const std::string line = daemon.readLine(std::chrono::seconds(20));
  ASSERT_NE(line.find("listening on"), std::string::npos) << line;
  httplib::Client cli("127.0.0.1", std::stoi(line.substr(line.rfind(':') + 1)));
  cli.set_read_timeout(30, 0);
  const std::string id = postHard(cli, bigStockJob(100));  // about 14 MB of STL
  ASSERT_FALSE(id.empty());
  const nlohmann::json doc = waitSettled(cli, id);
  EXPECT_EQ(doc["status"], "done");
  EXPECT_EQ(doc["report"]["status"], "clean");
  EXPECT_EQ(doc["mesh_error"]["code"], "mesh_write_failed");
  auto mesh = cli.Get(("/api/v1/jobs/" + id + "/mesh").c_str());
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->status, 409);
  EXPECT_TRUE(noMeshFiles(dir.path() / "data" / "meshes"));
  // The store takes and finishes further jobs, meshes included.
  const std::string small = postHard(cli, tinyJob());
  ASSERT_FALSE(small.empty());
  EXPECT_EQ(waitSettled(cli, small)["status"], "done");
  auto ok = cli.Get(("/api/v1/jobs/" + small + "/mesh").c_str());
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  EXPECT_EQ(getJson(cli, "/api/v1/jobs/" + id)["mesh_error"]["code"], "mesh_write_failed");
}

}  // namespace
}  // namespace mdhd::service_test

// Findings of a black-box probe of the job API, as a CAM system, an MES or a
// post-processor author's CI script would use it: byte ranges (a resumed mesh
// download; JSON replies must never be cut), and request metrics whose labels a
// client cannot multiply.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <string>
#include <vector>

#include "job_helpers.h"
#include "raw_socket.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

class HttpProbe : public ::testing::Test {
 protected:
  service::ServiceConfig config() { return testConfig(dir_.path()); }
  TempDir dir_;
};

// A finished tiny job's id.
std::string doneJob(httplib::Client& cli) {
  auto r = cli.Post("/api/v1/jobs", tinyJob().dump(), "application/json");
  if (!r || r->status != 202) return "";
  const std::string id = nlohmann::json::parse(r->body)["id"];
  const nlohmann::json doc = waitSettled(cli, id);
  return doc["status"] == "done" ? id : "";
}

TEST_F(HttpProbe, MeshByteRangesArePartialContentAndOutOfRangeIs416) {
  RunningService svc(config());
  auto cli = svc.client();
  cli->set_read_timeout(5, 0);  // a reply whose Content-Length lies would hang here
  const std::string id = doneJob(*cli);
  ASSERT_FALSE(id.empty());
  const std::string path = "/api/v1/jobs/" + id + "/mesh";
  auto whole = cli->Get(path.c_str());
  ASSERT_TRUE(whole);
  ASSERT_EQ(whole->status, 200);
  const std::string stl = whole->body;
  const std::size_t n = stl.size();
  ASSERT_GT(n, 200u);
  const std::string total = "/" + std::to_string(n);

  struct Case {
    std::string range;
    std::size_t first;
    std::size_t last;
  };
  for (const Case& c : {Case{"bytes=10-19", 10, 19}, Case{"bytes=-7", n - 7, n - 1},
                        Case{"bytes=" + std::to_string(n - 5) + "-", n - 5, n - 1},
                        Case{"bytes=100-99999999999", 100, n - 1}, Case{"bytes=0-0", 0, 0}}) {
    auto r = cli->Get(path.c_str(), {{"Range", c.range}});
    ASSERT_TRUE(r) << c.range;
    EXPECT_EQ(r->status, 206) << c.range;
    EXPECT_EQ(r->get_header_value("Content-Range"),
              "bytes " + std::to_string(c.first) + "-" + std::to_string(c.last) + total)
        << c.range;
    EXPECT_EQ(r->get_header_value("Content-Type"), "model/stl") << c.range;
    EXPECT_EQ(r->body, stl.substr(c.first, c.last - c.first + 1)) << c.range;
  }

  // Starting at or past the end: 416 with the size, as a JSON error, and the
  // connection still usable.
  for (const std::string& range :
       {"bytes=" + std::to_string(n) + "-", std::string("bytes=99999999-")}) {
    auto r = cli->Get(path.c_str(), {{"Range", range}});
    ASSERT_TRUE(r) << range;
    EXPECT_EQ(r->status, 416) << range;
    EXPECT_EQ(r->get_header_value("Content-Range"), "bytes */" + std::to_string(n)) << range;
    EXPECT_EQ(body(r)["error"]["code"], "range_not_satisfiable") << r->body;
  }

  // Forms the service does not serve get the whole file: several ranges, and an
  // If-Range (the service sends no validators, so none can match).
  auto many = cli->Get(path.c_str(), {{"Range", "bytes=0-1,4-5"}});
  ASSERT_TRUE(many);
  EXPECT_EQ(many->status, 200);
  EXPECT_EQ(many->body, stl);
  auto ifRange = cli->Get(path.c_str(), {{"Range", "bytes=0-9"}, {"If-Range", "\"x\""}});
  ASSERT_TRUE(ifRange);
  EXPECT_EQ(ifRange->status, 200);
  EXPECT_EQ(ifRange->body, stl);
  auto head = cli->Head(path.c_str());
  ASSERT_TRUE(head);
  EXPECT_EQ(head->get_header_value("Accept-Ranges"), "bytes");
}

TEST_F(HttpProbe, JsonRepliesAreNeverCutByARange) {
  RunningService svc(config());
  auto cli = svc.client();
  const std::string id = doneJob(*cli);
  ASSERT_FALSE(id.empty());
  for (const std::string& path :
       {"/api/v1/jobs/" + id, std::string("/api/v1/jobs?limit=5"), std::string("/api/v1/jobs/0123"),
        std::string("/nope"), std::string("/healthz"), std::string("/openapi.json")}) {
    auto plain = cli->Get(path.c_str());
    ASSERT_TRUE(plain) << path;
    for (const char* range : {"bytes=0-5", "bytes=-3", "bytes=0-1,5-6", "bytes=100000-"}) {
      auto r = cli->Get(path.c_str(), {{"Range", range}});
      ASSERT_TRUE(r) << path << " " << range;
      EXPECT_EQ(r->status, plain->status) << path << " " << range;
      EXPECT_FALSE(r->has_header("Content-Range")) << path << " " << range;
      EXPECT_FALSE(nlohmann::json::parse(r->body, nullptr, false).is_discarded())
          << path << " " << range << ": " << r->body;
    }
  }
  auto post = cli->Post("/api/v1/jobs", {{"Range", "bytes=0-5"}}, "{", "application/json");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 400);
  EXPECT_EQ(body(post)["error"]["code"], "bad_json") << post->body;
  // HEAD says ranges are not served here (cpp-httplib said "bytes" on every HEAD).
  auto head = cli->Head(("/api/v1/jobs/" + id).c_str());
  ASSERT_TRUE(head);
  EXPECT_EQ(head->get_header_value("Accept-Ranges"), "none");
}

TEST_F(HttpProbe, TheJobListRefusesQueryParametersItDoesNotHave) {
  RunningService svc(config());
  auto cli = svc.client();
  for (int i = 0; i < 3; ++i) {
    auto r = cli->Post("/api/v1/jobs", tinyJob(i).dump(), "application/json");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 202);
  }
  // A script paging by offset, or filtering by status, was given the first page of
  // everything, as if the parameter had worked.
  for (const std::string& query : {std::string("limit=1&offset=1"), std::string("status=failed"),
                                   std::string("limit=1&limit=2"), std::string("Limit=1")}) {
    auto r = cli->Get(("/api/v1/jobs?" + query).c_str());
    ASSERT_TRUE(r) << query;
    EXPECT_EQ(r->status, 400) << query << ": " << r->body;
    EXPECT_EQ(body(r)["error"]["code"], "bad_parameter") << r->body;
    EXPECT_TRUE(body(r)["error"]["parameter"].is_string()) << r->body;
  }
  auto page = cli->Get("/api/v1/jobs?limit=2");
  ASSERT_TRUE(page);
  ASSERT_EQ(page->status, 200);
  const std::string cursor = body(page)["next_cursor"];
  auto next = cli->Get(("/api/v1/jobs?cursor=" + cursor + "&limit=2").c_str());
  ASSERT_TRUE(next);
  EXPECT_EQ(next->status, 200);
  EXPECT_EQ(body(next)["jobs"].size(), 1u) << next->body;
}

TEST_F(HttpProbe, OpenApiListsTheStatusesTheRoutesAnswer) {
  service::ServiceConfig c = config();
  const std::string token = "0123456789abcdef-probe-token";
  c.tokens = {token};
  c.max_body_bytes = 4096;
  RunningService svc(c);
  auto open = svc.client();
  auto doc = open->Get("/openapi.json");
  ASSERT_TRUE(doc);
  const nlohmann::json api = body(doc);
  auto documented = [&api](const std::string& path, std::string method, int status) {
    for (char& ch : method) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return api["paths"][path][method]["responses"].contains(std::to_string(status));
  };
  auto authed = svc.client(token);
  const std::string machine = threeAxisMachine().dump();
  struct Probe {
    const char* method;
    std::string url;
    std::string path;  // the template
    std::string body;
    const char* type;
    bool withToken;
  };
  const std::vector<Probe> probes = {
      {"PUT", "/api/v1/machines/m1", "/api/v1/machines/{name}", machine, "text/plain", true},
      {"PUT", "/api/v1/machines/m1", "/api/v1/machines/{name}", std::string(5000, ' '),
       "application/json", true},
      {"PUT", "/api/v1/machines/m1", "/api/v1/machines/{name}", machine, "application/json", false},
      {"GET", "/api/v1/machines/m1", "/api/v1/machines/{name}", "", "", false},
      {"GET", "/api/v1/jobs/0123", "/api/v1/jobs/{id}", "", "", false},
      {"DELETE", "/api/v1/machines/m1", "/api/v1/machines/{name}", "", "", false},
      {"POST", "/api/v1/shadows", "/api/v1/shadows", "{}", "text/plain", true},
      {"GET", "/api/v1/jobs", "/api/v1/jobs", "", "", false},
  };
  for (const Probe& p : probes) {
    httplib::Client& cli = p.withToken ? *authed : *open;
    httplib::Result r = std::string(p.method) == "PUT"    ? cli.Put(p.url.c_str(), p.body, p.type)
                        : std::string(p.method) == "POST" ? cli.Post(p.url.c_str(), p.body, p.type)
                        : std::string(p.method) == "DELETE" ? cli.Delete(p.url.c_str())
                                                            : cli.Get(p.url.c_str());
    ASSERT_TRUE(r) << p.method << " " << p.url;
    EXPECT_GE(r->status, 400) << p.method << " " << p.url;
    EXPECT_TRUE(documented(p.path, p.method, r->status))
        << p.method << " " << p.path << " answered " << r->status << " (" << r->body
        << ") which the OpenAPI document does not list";
  }
}

TEST_F(HttpProbe, AKeyGivenTwiceIsRefusedNotSilentlyOverwritten) {
  RunningService svc(config());
  auto cli = svc.client();
  // A templated job with two "options": the parser kept the last one and the job
  // ran at the wrong density with a 202.
  std::string job = tinyJob().dump();
  job.insert(job.size() - 1, R"(,"options":{"density":40})");
  auto r = cli->Post("/api/v1/jobs", job, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_EQ(body(r)["error"]["code"], "bad_json") << r->body;
  EXPECT_EQ(body(r)["error"]["field"], "options") << r->body;

  nlohmann::json twoTools = tinyJob();
  twoTools["tools"].push_back(twoTools["tools"][0]);
  twoTools["tools"][1]["number"] = 2;
  std::string text = twoTools.dump();
  text.insert(text.rfind(R"("number":2)"), R"("number":3,)");
  r = cli->Post("/api/v1/jobs", text, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_EQ(body(r)["error"]["field"], "tools[1].number") << r->body;

  r = cli->Put("/api/v1/machines/twice", R"({"name": "a", "name": "b"})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_EQ(body(r)["error"]["field"], "name") << r->body;

  // The same key in different objects is fine.
  r = cli->Post("/api/v1/jobs", tinyJob().dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202) << r->body;
}

// One raw request on its own connection; what came back before the first reply's
// status line ended or 5 s passed.
std::string rawFirstLine(int port, const std::string& request) {
  const int fd = connectLoopback(port);
  if (fd < 0) return "";
  std::size_t off = 0;
  while (off < request.size()) {
    const ssize_t n = send(fd, request.data() + off, request.size() - off, MSG_NOSIGNAL);
    if (n <= 0) break;
    off += static_cast<std::size_t>(n);
  }
  std::string reply;
  char buf[4096];
  pollfd p{fd, POLLIN, 0};
  while (reply.find("\r\n") == std::string::npos && poll(&p, 1, 5000) > 0) {
    const ssize_t n = recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    reply.append(buf, static_cast<std::size_t>(n));
  }
  close(fd);
  return reply.substr(0, reply.find("\r\n"));
}

// The status of the reply to a raw request (0: none).
int rawStatus(int port, const std::string& request) {
  const std::string line = rawFirstLine(port, request);
  return line.size() > 12 ? std::atoi(line.c_str() + 9) : 0;
}

TEST_F(HttpProbe, ExpectContinueIsAnsweredByTheScreenNotInvitedFirst) {
  service::ServiceConfig c = config();
  c.max_body_bytes = 4096;
  c.tokens = {"0123456789abcdef-probe-token"};
  RunningService svc(c);
  // curl sends `Expect: 100-continue` before any body over 1 MB and waits: the
  // library said "100 Continue" before the screen ran, so the client uploaded the
  // whole body to learn it was too large, unauthorised or sent to no route.
  const std::string auth = "Authorization: Bearer 0123456789abcdef-probe-token\r\n";
  const std::string expect = "Content-Type: application/json\r\nExpect: 100-continue\r\n";
  EXPECT_EQ(rawFirstLine(svc->port(), "POST /api/v1/jobs HTTP/1.1\r\nHost: x\r\n" + auth + expect +
                                          "Content-Length: 50000000\r\n\r\n"),
            "HTTP/1.1 413 Payload Too Large");
  EXPECT_EQ(rawFirstLine(svc->port(), "POST /api/v1/jobs HTTP/1.1\r\nHost: x\r\n" + expect +
                                          "Content-Length: 100\r\n\r\n"),
            "HTTP/1.1 401 Unauthorized");
  EXPECT_EQ(rawFirstLine(svc->port(), "POST /api/v1/nothing HTTP/1.1\r\nHost: x\r\n" + auth +
                                          expect + "Content-Length: 100\r\n\r\n"),
            "HTTP/1.1 404 Not Found");
  // A request the screen passes is still invited.
  EXPECT_EQ(rawFirstLine(svc->port(), "POST /api/v1/jobs HTTP/1.1\r\nHost: x\r\n" + auth + expect +
                                          "Content-Length: 100\r\n\r\n"),
            "HTTP/1.1 100 Continue");
  // And the refusal is a whole JSON error a library client can read.
  auto cli = svc.client("0123456789abcdef-probe-token");
  auto r = cli->Post("/api/v1/jobs", {{"Expect", "100-continue"}}, std::string(5000, ' '),
                     "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_EQ(body(r)["error"]["code"], "body_too_large") << r->body;
}

TEST_F(HttpProbe, RequestMetricsKeepOneMethodLabelForUnknownMethods) {
  RunningService svc(config());
  // Any token is a method to the parser; each one was a series of its own, kept
  // forever and sent on every scrape (no token needed to add one).
  const int kMethods = 40;
  for (int i = 0; i < kMethods; ++i) {
    const std::string method = "M" + std::to_string(i) + std::string(500, 'X') + "\xff";
    EXPECT_NE(rawStatus(svc->port(), method + " /healthz HTTP/1.1\r\nHost: x\r\n\r\n"), 0);
  }
  auto cli = svc.client();
  auto r = cli->Get("/metrics");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->body.find("XXXX"), std::string::npos);
  EXPECT_EQ(r->body.find('\xff'), std::string::npos);
  std::size_t series = 0;
  std::uint64_t other = 0;
  std::size_t at = 0;
  const std::string name = "mdhd_http_requests_total{";
  while ((at = r->body.find(name, at)) != std::string::npos) {
    const std::size_t end = r->body.find('\n', at);
    const std::string line = r->body.substr(at, end - at);
    ++series;
    if (line.find("method=\"other\"") != std::string::npos)
      other += std::stoull(line.substr(line.rfind(' ') + 1));
    at = end;
  }
  EXPECT_LE(series, 3u) << r->body;
  EXPECT_EQ(other, static_cast<std::uint64_t>(kMethods)) << r->body;
}

}  // namespace
}  // namespace mdhd::service_test

// Findings of a black-box probe of the job API, as a CAM system, an MES or a
// post-processor author's CI script would use it: byte ranges (a resumed mesh
// download; JSON replies must never be cut).
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "job_helpers.h"
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

}  // namespace
}  // namespace mdhd::service_test

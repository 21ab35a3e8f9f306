// The HTTP front on its own: routing by path template, auth, JSON errors, the
// log line and the metrics every route gets, /healthz, /metrics, /openapi.json.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "daemon/http_errors.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

const std::string kToken = "0123456789abcdef-test-token";

// A route group as another file would add it: echoes its path parameters.
void addEchoRoutes(service::HttpService& http) {
  http.route({"GET", "/api/v1/echo/{a}/x/{b}", {{"summary", "echo"}}},
             [](const httplib::Request& req, httplib::Response& res) {
               service::sendJson(
                   res, 200,
                   {{"a", service::pathParam(req, 1)}, {"b", service::pathParam(req, 2)}});
             });
  http.route({"POST", "/api/v1/echo", {{"summary", "echo a body"}}}, [](const httplib::Request& req,
                                                                        httplib::Response& res) {
    const nlohmann::json doc = service::parseJsonBody(req);
    if (!doc.is_object()) {
      throw service::HttpError(400, "bad_field", "an object please", {{"field", "(document)"}});
    }
    service::sendJson(res, 200, doc);
  });
  http.route({"GET", "/api/v1/boom", {{"summary", "fails"}}},
             [](const httplib::Request&, httplib::Response&) {
               throw std::logic_error("secret internal detail");
             });
}

TEST(HttpService, PathTemplatesBecomeOneSegmentCaptures) {
  EXPECT_EQ(service::pathPattern("/api/v1/jobs/{id}/mesh"), "/api/v1/jobs/([^/]+)/mesh");
  EXPECT_EQ(service::pathPattern("/openapi.json"), "/openapi\\.json");
}

TEST(HttpService, HealthzMetricsAndRoutesOfAnotherGroup) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()), false);
  addEchoRoutes(svc->http());
  svc.start();
  auto cli = svc.client();
  auto health = cli->Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(body(health)["status"], "ok");

  auto echo = cli->Get("/api/v1/echo/one/x/t%20wo");
  ASSERT_TRUE(echo);
  EXPECT_EQ(echo->status, 200);
  EXPECT_EQ(body(echo)["a"], "one");
  EXPECT_EQ(body(echo)["b"], "t wo");

  auto posted = cli->Post("/api/v1/echo", R"({"k": [1, 2]})", "application/json");
  ASSERT_TRUE(posted);
  EXPECT_EQ(posted->status, 200);
  EXPECT_EQ(body(posted)["k"][1], 2);

  auto metrics = cli->Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->status, 200);
  EXPECT_NE(
      metrics->body.find("mdhd_http_requests_total{route=\"/api/v1/echo/{a}/x/{b}\",method=\"GET\","
                         "status=\"200\"} 1"),
      std::string::npos)
      << metrics->body;
  EXPECT_NE(metrics->body.find("mdhd_http_request_duration_seconds_count"), std::string::npos);
}

TEST(HttpService, ErrorsAreJsonWithTheRightStatus) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()), false);
  addEchoRoutes(svc->http());
  svc.start();
  auto cli = svc.client();

  auto missing = cli->Get("/api/v1/nothing-here");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(body(missing)["error"]["code"], "not_found");

  auto wrongMethod = cli->Delete("/api/v1/echo");
  ASSERT_TRUE(wrongMethod);
  EXPECT_EQ(wrongMethod->status, 405);
  EXPECT_EQ(wrongMethod->get_header_value("Allow"), "POST");
  // A GET route answers HEAD too, and says so.
  auto post = cli->Post("/healthz", "", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 405);
  EXPECT_EQ(post->get_header_value("Allow"), "GET, HEAD");

  auto badJson = cli->Post("/api/v1/echo", "{\"k\": [1, 2", "application/json");
  ASSERT_TRUE(badJson);
  EXPECT_EQ(badJson->status, 400);
  EXPECT_EQ(body(badJson)["error"]["code"], "bad_json");
  EXPECT_NE(body(badJson)["error"]["message"].get<std::string>().find("line 1"), std::string::npos);

  auto deep = cli->Post("/api/v1/echo", std::string(100000, '[') + std::string(100000, ']'),
                        "application/json");
  ASSERT_TRUE(deep);
  EXPECT_EQ(deep->status, 400);

  auto notJson = cli->Post("/api/v1/echo", "a=b", "application/x-www-form-urlencoded");
  ASSERT_TRUE(notJson);
  EXPECT_EQ(notJson->status, 415);

  auto field = cli->Post("/api/v1/echo", "[1]", "application/json");
  ASSERT_TRUE(field);
  EXPECT_EQ(field->status, 400);
  EXPECT_EQ(body(field)["error"]["field"], "(document)");

  auto boom = cli->Get("/api/v1/boom");
  ASSERT_TRUE(boom);
  EXPECT_EQ(boom->status, 500);
  EXPECT_EQ(boom->body.find("secret"), std::string::npos);
}

TEST(HttpService, BodiesOverTheLimitAre413) {
  TempDir dir;
  service::ServiceConfig config = testConfig(dir.path());
  config.max_body_bytes = 4096;
  RunningService svc(config, false);
  addEchoRoutes(svc->http());
  svc.start();
  auto cli = svc.client();
  auto big = cli->Post("/api/v1/echo", "\"" + std::string(5000, 'x') + "\"", "application/json");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  EXPECT_EQ(body(big)["error"]["code"], "body_too_large");
  auto small = cli->Post("/api/v1/echo", R"({"fits": true})", "application/json");
  ASSERT_TRUE(small);
  EXPECT_EQ(small->status, 200);
}

TEST(HttpService, TokensAreCheckedOnEveryRouteButHealthz) {
  TempDir dir;
  service::ServiceConfig config = testConfig(dir.path());
  config.tokens = {kToken};
  RunningService svc(config, false);
  addEchoRoutes(svc->http());
  svc.start();

  auto anonymous = svc.client();
  auto open = anonymous->Get("/healthz");
  ASSERT_TRUE(open);
  EXPECT_EQ(open->status, 200);
  for (const char* path : {"/api/v1/echo/a/x/b", "/metrics"}) {
    auto r = anonymous->Get(path);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 401) << path;
    EXPECT_EQ(body(r)["error"]["code"], "unauthorized");
    EXPECT_EQ(r->get_header_value("WWW-Authenticate"), "Bearer");
  }
  auto basic = anonymous->Get("/metrics", {{"Authorization", "Basic dXNlcjpwYXNz"}});
  ASSERT_TRUE(basic);
  EXPECT_EQ(basic->status, 401);

  auto wrong = svc.client("0123456789abcdef-wrong-token");
  auto denied = wrong->Get("/api/v1/echo/a/x/b");
  ASSERT_TRUE(denied);
  EXPECT_EQ(denied->status, 403);
  EXPECT_EQ(body(denied)["error"]["code"], "forbidden");

  auto right = svc.client(kToken);
  auto ok = right->Get("/api/v1/echo/a/x/b");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
}

TEST(HttpService, RefusesToBindBeyondLoopbackWithoutTokens) {
  TempDir dir;
  service::ServiceConfig config = testConfig(dir.path());
  config.bind = "0.0.0.0";
  EXPECT_THROW(service::Service svc(config), std::runtime_error);
  config.tokens = {kToken};
  EXPECT_NO_THROW(service::Service svc(config));
}

TEST(HttpService, OpenApiListsEveryRoute) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()), false);
  addEchoRoutes(svc->http());
  svc.start();
  auto r = svc.client()->Get("/openapi.json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const nlohmann::json doc = body(r);
  EXPECT_EQ(doc["openapi"], "3.1.0");
  for (const char* path : {"/healthz", "/metrics", "/openapi.json", "/api/v1/echo/{a}/x/{b}"}) {
    EXPECT_TRUE(doc["paths"].contains(path)) << path;
  }
  const auto& params = doc["paths"]["/api/v1/echo/{a}/x/{b}"]["get"]["parameters"];
  ASSERT_EQ(params.size(), 2u);
  EXPECT_EQ(params[1]["name"], "b");
}

TEST(HttpService, EveryRequestIsOneJsonLogLine) {
  TempDir dir;
  {
    RunningService svc(testConfig(dir.path()));
    auto cli = svc.client();
    ASSERT_TRUE(cli->Get("/healthz"));
    ASSERT_TRUE(cli->Get("/nope"));
  }
  std::ifstream in(dir.path() / "log.jsonl");
  std::string line;
  int requests = 0;
  std::set<int> statuses;
  while (std::getline(in, line)) {
    const nlohmann::json j = nlohmann::json::parse(line);  // every line parses
    ASSERT_TRUE(j.contains("ts"));
    if (j["event"] == "request") {
      ++requests;
      statuses.insert(j["status"].get<int>());
    }
  }
  EXPECT_EQ(requests, 2);
  EXPECT_EQ(statuses, (std::set<int>{200, 404}));
}

}  // namespace
}  // namespace mdhd::service_test

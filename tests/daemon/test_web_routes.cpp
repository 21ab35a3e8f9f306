// The browser UI as the service serves it: every embedded file with its type and
// security headers, revalidation by ETag, open without a token, and a page whose
// references all resolve to files the executable carries.
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>

#include "daemon/web_assets.h"
#include "tests/daemon/service_fixture.h"

namespace mdhd::service_test {
namespace {

TEST(WebRoutes, ThePageAndEveryFileAreServedWithTheirTypeAndHeaders) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()));
  auto client = svc.client();
  const auto page = client->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page->body.find("<!doctype html>"), std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("frame-ancestors 'none'"),
            std::string::npos);
  EXPECT_EQ(page->get_header_value("X-Content-Type-Options"), "nosniff");

  ASSERT_FALSE(service::embeddedWebFiles().empty());
  for (const service::EmbeddedFile& f : service::embeddedWebFiles()) {
    const auto r = client->Get("/ui/" + std::string(f.name));
    ASSERT_TRUE(r) << f.name;
    EXPECT_EQ(r->status, 200) << f.name;
    EXPECT_EQ(r->body, f.body) << f.name;
    EXPECT_EQ(r->get_header_value("Content-Type"), service::mimeTypeFor(f.name)) << f.name;
  }
  EXPECT_EQ(service::mimeTypeFor("app.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(service::mimeTypeFor("style.css"), "text/css; charset=utf-8");
}

TEST(WebRoutes, UnknownFilesAre404JsonAndPathsDoNotEscape) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()));
  auto client = svc.client();
  for (const std::string path :
       {"/ui/nothing.js", "/ui/..%2Fservice.cpp", "/ui/%2e%2e", "/ui/index.html%00.js", "/ui/"}) {
    const auto r = client->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_EQ(body(r)["error"]["code"], "not_found") << path << " " << r->body;
  }
  const auto post = client->Post("/", "x", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 405);
}

TEST(WebRoutes, UnchangedFilesAnswer304ToTheirETag) {
  TempDir dir;
  RunningService svc(testConfig(dir.path()));
  auto client = svc.client();
  const auto first = client->Get("/");
  ASSERT_TRUE(first);
  const std::string etag = first->get_header_value("ETag");
  ASSERT_FALSE(etag.empty());
  const auto again = client->Get("/", {{"If-None-Match", etag}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
  EXPECT_TRUE(again->body.empty());
  const auto other = client->Get("/", {{"If-None-Match", "\"0000\""}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200);
}

TEST(WebRoutes, TheUiIsOpenWhileTheApiWantsTheToken) {
  TempDir dir;
  service::ServiceConfig config = testConfig(dir.path());
  config.tokens = {"a-long-enough-secret-token"};
  RunningService svc(config);
  auto client = svc.client();
  const auto page = client->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  const auto jobs = client->Get("/api/v1/jobs");
  ASSERT_TRUE(jobs);
  EXPECT_EQ(jobs->status, 401);
}

// Every "/ui/NAME" the page names and every "./NAME" a script imports is a file the
// executable carries: a renamed module fails here, not in a user's browser.
TEST(WebRoutes, EveryReferenceInThePageAndScriptsResolves) {
  std::set<std::string> names;
  for (const service::EmbeddedFile& f : service::embeddedWebFiles())
    names.insert(std::string(f.name));
  ASSERT_TRUE(names.count("index.html"));
  const std::regex pageRef(R"re((?:src|href)="/ui/([^"]+)")re");
  const std::regex importRef(R"re((?:from|import)\s*\(?\s*["']\./([^"']+)["'])re");
  int checked = 0;
  for (const service::EmbeddedFile& f : service::embeddedWebFiles()) {
    const std::string text(f.body);
    const std::regex& re = f.name == "index.html" ? pageRef : importRef;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
         ++it) {
      EXPECT_TRUE(names.count((*it)[1].str())) << f.name << " refers to " << (*it)[1].str();
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace mdhd::service_test

// Settings of mdhd serve: defaults, file < environment < flags, strict values, the
// loopback rule.
#include <gtest/gtest.h>

#include <fstream>

#include "daemon/number_text.h"
#include "daemon/service_config.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

using service::ServiceConfig;

TEST(ServiceConfig, EmbeddedDefaultsServeLoopbackWithoutConfiguration) {
  const ServiceConfig c;
  EXPECT_EQ(c.bind, "127.0.0.1");
  EXPECT_EQ(c.port, 8080);
  EXPECT_EQ(c.data_dir, "var/mdhd");
  EXPECT_TRUE(c.example_machines);
  EXPECT_EQ(service::configProblem(c), "");
  EXPECT_GE(service::effectiveWorkers(c), 1);
}

TEST(ServiceConfig, FileThenEnvironmentThenFlags) {
  TempDir dir;
  const std::string path = (dir.path() / "mdhd.json").string();
  std::ofstream(path) << R"({"port": 9000, "workers": 3, "queue_limit": 5,
    "tokens": ["file-token-0123456789"], "max_job_seconds": 60, "data_dir": "/srv/mdhd"})";
  ServiceConfig c;
  const std::vector<std::string> flags = {"--config", path,      "--port",
                                          "9002",     "--token", "flag-token-0123456789"};
  const std::map<std::string, std::string> env = {
      {"MDHD_PORT", "9001"}, {"MDHD_WORKERS", "4"}, {"MDHD_UNRELATED", "x"}};
  EXPECT_EQ(service::configPath(flags, env), path);
  service::applyConfigFile(c, service::configPath(flags, env));
  service::applyEnvironment(c, env);
  service::applyFlags(c, flags);
  EXPECT_EQ(c.port, 9002);             // flag over env over file
  EXPECT_EQ(c.workers, 4);             // env over file
  EXPECT_EQ(c.queue_limit, 5u);        // file over default
  EXPECT_EQ(c.data_dir, "/srv/mdhd");  // file
  EXPECT_EQ(c.tokens, std::vector<std::string>{"flag-token-0123456789"});  // flags replace
  EXPECT_EQ(c.max_job_seconds, 60.0);
  EXPECT_EQ(service::configPath({}, {{"MDHD_CONFIG", "/etc/mdhd.json"}}), "/etc/mdhd.json");
}

TEST(ServiceConfig, BadValuesNameTheirSource) {
  TempDir dir;
  const std::string path = (dir.path() / "bad.json").string();
  std::ofstream(path) << R"({"port": 70000})";
  ServiceConfig c;
  try {
    service::applyConfigFile(c, path);
    FAIL() << "port 70000 accepted";
  } catch (const protocol::FieldError& e) {
    EXPECT_NE(e.field().find("port"), std::string::npos);
  }
  std::ofstream(path) << R"({"prot": 8080})";
  EXPECT_THROW(service::applyConfigFile(c, path), protocol::FieldError);
  std::ofstream(path) << "{not json";
  EXPECT_THROW(service::applyConfigFile(c, path), protocol::FieldError);
  EXPECT_THROW(service::applyEnvironment(c, {{"MDHD_WORKERS", "many"}}), protocol::FieldError);
  EXPECT_THROW(service::applyFlags(c, {"--port"}), protocol::FieldError);
  EXPECT_THROW(service::applyFlags(c, {"--frobnicate", "1"}), protocol::FieldError);
  EXPECT_THROW(service::applyFlags(c, {"--max-job-seconds", "-1"}), protocol::FieldError);
  EXPECT_THROW(service::applyConfigFile(c, (dir.path() / "missing.json").string()),
               protocol::FieldError);
}

// Integers in flags, the environment and query strings are digits with an optional
// '-': std::stoll alone took " 80", "+2" and "\t3" as numbers.
TEST(ServiceConfig, IntegersAreDigitsOnly) {
  EXPECT_EQ(service::integerInRange("80", 0, 65535), 80);
  EXPECT_EQ(service::integerInRange("-5", -10, 10), -5);
  EXPECT_EQ(service::integerInRange("007", 0, 10), 7);
  for (const char* bad : {"", "-", "+2", " 80", "80 ", "\t3", "8O", "0x10", "1e3", "--1"}) {
    EXPECT_FALSE(service::integerInRange(bad, -100000, 100000)) << "'" << bad << "'";
  }
  EXPECT_FALSE(service::integerInRange("99999999999999999999", 0, 10));
  ServiceConfig c;
  EXPECT_THROW(service::applyFlags(c, {"--port", "+80"}), protocol::FieldError);
}

TEST(ServiceConfig, BeyondLoopbackNeedsLongTokens) {
  ServiceConfig c;
  for (const char* host : {"127.0.0.1", "127.1.2.3", "::1", "localhost"}) {
    EXPECT_TRUE(service::isLoopback(host)) << host;
  }
  for (const char* host : {"0.0.0.0", "10.0.0.5", "::", "128.0.0.1"}) {
    EXPECT_FALSE(service::isLoopback(host)) << host;
  }
  c.bind = "0.0.0.0";
  EXPECT_NE(service::configProblem(c).find("token"), std::string::npos);
  c.tokens = {"short"};
  EXPECT_NE(service::configProblem(c).find("shorter"), std::string::npos);
  c.tokens = {"a-long-enough-token-1234"};
  EXPECT_EQ(service::configProblem(c), "");
}

}  // namespace
}  // namespace mdhd::service_test

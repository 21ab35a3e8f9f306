// Property test of the request parsing paths: random bytes, random JSON, and
// random mutations of a valid job and machine, posted to the real service. Every
// reply must be one of the contract's statuses with a JSON error body: never a
// 500, a crash or a hang. MDHD_FUZZ_ITERATIONS raises the count (default 300).
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <random>

#include "job_helpers.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

class RandomJson {
 public:
  explicit RandomJson(std::uint32_t seed) : rng_(seed) {}

  int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

  nlohmann::json value(int depth = 0) {
    switch (below(depth > 2 ? 6 : 8)) {
      case 0:
        return nullptr;
      case 1:
        return below(2) == 0;
      case 2:
        return below(60) - 10;
      case 3:
        return std::uniform_real_distribution<double>(-20, 60)(rng_);
      case 4:
        return text();
      case 5:
        return below(2) == 0 ? nlohmann::json(1e300) : nlohmann::json(-0.0);
      case 6: {
        nlohmann::json a = nlohmann::json::array();
        for (int i = below(4); i > 0; --i) a.push_back(value(depth + 1));
        return a;
      }
      default: {
        nlohmann::json o = nlohmann::json::object();
        for (int i = below(4); i > 0; --i) o[text()] = value(depth + 1);
        return o;
      }
    }
  }

  std::string text() {
    static const char* kWords[] = {"",     "x",          "G1 X",         "machine",  "tools",
                                   "flat", "3axis-mill", "G21\nG0 Z5\n", "\xff\xfe", "min",
                                   "box",  "A",          "..",           "/"};
    return kWords[below(14)];
  }

  std::string bytes() {
    std::string s(static_cast<std::size_t>(below(120)), ' ');
    for (char& c : s) c = static_cast<char>(below(256));
    return s;
  }

  // Replaces, removes or adds one member somewhere inside `doc`.
  void mutate(nlohmann::json& doc) {
    nlohmann::json* at = &doc;
    for (int depth = 0; depth < 4 && (at->is_object() || at->is_array()) && !at->empty(); ++depth) {
      if (below(3) == 0) break;
      if (at->is_object()) {
        auto it = at->begin();
        std::advance(it, below(static_cast<int>(at->size())));
        at = &it.value();
      } else {
        at = &(*at)[static_cast<std::size_t>(below(static_cast<int>(at->size())))];
      }
    }
    if (at->is_object() && !at->empty() && below(3) == 0) {
      auto it = at->begin();
      std::advance(it, below(static_cast<int>(at->size())));
      at->erase(it);
    } else if (at->is_object() && below(2) == 0) {
      (*at)[text()] = value();
    } else {
      *at = value();
    }
  }

 private:
  std::mt19937 rng_;
};

bool allowed(int status) {
  for (int s : {200, 201, 202, 400, 404, 405, 409, 413, 415, 422, 429, 503}) {
    if (status == s) return true;
  }
  return false;
}

TEST(RequestFuzz, NoBodyMakesTheServiceFail) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.queue_limit = 4;
  c.shutdown_grace_seconds = 0;
  c.max_body_bytes = 256 * 1024;
  RunningService svc(c);
  auto cli = svc.client();
  const char* env = std::getenv("MDHD_FUZZ_ITERATIONS");
  const int iterations = env != nullptr ? std::atoi(env) : 300;
  RandomJson random(20261122);
  const std::string validJob = tinyJob().dump();
  const nlohmann::json validMachine = threeAxisMachine();
  std::map<int, int> statuses;
  for (int i = 0; i < iterations; ++i) {
    std::string path = "/api/v1/jobs";
    std::string text;
    bool put = false;
    switch (i % 6) {
      case 0:
        text = random.bytes();
        break;
      case 1:
        text = random.value().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        break;
      case 2:
        text = validJob.substr(
            0, static_cast<std::size_t>(random.below(static_cast<int>(validJob.size()))));
        break;
      case 3: {
        nlohmann::json machine = validMachine;
        for (int k = 1 + random.below(3); k > 0; --k) random.mutate(machine);
        text = machine.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        path = "/api/v1/machines/fuzz-" + std::to_string(i);
        put = true;
        break;
      }
      default: {
        nlohmann::json job = tinyJob(i);
        for (int k = 1 + random.below(3); k > 0; --k) random.mutate(job);
        text = job.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      }
    }
    auto r = put ? cli->Put(path.c_str(), text, "application/json")
                 : cli->Post(path.c_str(), text, "application/json");
    ASSERT_TRUE(r) << "no reply to: " << text.substr(0, 300);
    ++statuses[r->status];
    ASSERT_TRUE(allowed(r->status)) << r->status << " for: " << text.substr(0, 300) << "\n"
                                    << r->body;
    if (r->status >= 400) {
      const nlohmann::json doc = nlohmann::json::parse(r->body, nullptr, false);
      ASSERT_TRUE(doc.is_object() && doc["error"]["code"].is_string()) << r->body;
    }
    auto q = cli->Get(("/api/v1/jobs?limit=" + random.text() +
                       "&cursor=" + std::to_string(random.below(100) - 50))
                          .c_str());
    ASSERT_TRUE(q);
    ASSERT_TRUE(q->status == 200 || q->status == 400) << q->status;
  }
  for (const auto& [status, n] : statuses) std::cout << "status " << status << ": " << n << "\n";
  // The property is only worth something if the mutations reach past the JSON parser.
  EXPECT_GT(statuses[400], iterations / 10);
  EXPECT_GT(statuses[202] + statuses[201] + statuses[200] + statuses[429] + statuses[422], 0);
  auto health = cli->Get("/healthz");
  ASSERT_TRUE(health);
}

}  // namespace
}  // namespace mdhd::service_test

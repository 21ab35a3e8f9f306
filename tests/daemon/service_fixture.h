#pragma once
// A Service on a free loopback port with its data in a fresh temporary folder,
// started in the constructor and stopped (joined) in the destructor, and an
// HTTP client for it.
#include <httplib.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "daemon/service.h"

namespace mdhd::service_test {

// A folder under the system temp dir, removed with everything in it at the end.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("mdhd-daemon-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline service::ServiceConfig testConfig(const std::filesystem::path& dir) {
  service::ServiceConfig c;
  c.port = 0;
  c.data_dir = (dir / "data").string();
  c.log_file = (dir / "log.jsonl").string();
  c.workers = 1;
  c.http_threads = 8;
  return c;
}

class RunningService {
 public:
  explicit RunningService(service::ServiceConfig config, bool start = true)
      : service_(std::make_unique<service::Service>(std::move(config))) {
    if (start) this->start();
  }
  ~RunningService() { service_->stop(); }
  void start() { service_->start(); }
  service::Service& operator*() { return *service_; }
  service::Service* operator->() { return service_.get(); }

  std::unique_ptr<httplib::Client> client(const std::string& token = "") const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", service_->port());
    c->set_tcp_nodelay(true);
    c->set_read_timeout(30, 0);
    if (!token.empty()) c->set_bearer_token_auth(token);
    return c;
  }

 private:
  std::unique_ptr<service::Service> service_;
};

inline nlohmann::json body(const httplib::Result& r) {
  return nlohmann::json::parse(r->body, nullptr, false);
}

}  // namespace mdhd::service_test

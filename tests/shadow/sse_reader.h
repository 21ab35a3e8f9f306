#pragma once
// A Server-Sent Events client for the tests and the benchmark: reads a stream on
// a thread of its own with cpp-httplib and keeps each event with the time it
// arrived.
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

namespace mdhd::shadow::testing {

struct ReceivedEvent {
  std::uint64_t id = 0;
  std::string type;
  nlohmann::json data;
  std::chrono::steady_clock::time_point at;
};

class SseReader {
 public:
  SseReader(int port, const std::string& path) : client_("127.0.0.1", port) {
    client_.set_tcp_nodelay(true);
    client_.set_read_timeout(30, 0);
    thread_ = std::thread([this, path] {
      const auto r = client_.Get(path.c_str(), [this](const char* data, std::size_t n) {
        feed(std::string(data, n));
        return !stop_;
      });
      std::lock_guard lock(mutex_);
      if (r) status_ = r->status;
      ended_ = true;
      changed_.notify_all();
    });
  }
  ~SseReader() {
    stop_ = true;
    client_.stop();
    thread_.join();
  }

  // Waits until an event satisfies `pred` (true) or `limit` passes (false).
  bool waitFor(const std::function<bool(const ReceivedEvent&)>& pred,
               std::chrono::milliseconds limit) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, limit, [&] {
      for (const ReceivedEvent& e : events_)
        if (pred(e)) return true;
      return false;
    });
  }
  // The n-th (1-based) event of `type`, waiting up to `limit` for it.
  std::optional<ReceivedEvent> waitNth(const std::string& type, std::size_t n,
                                       std::chrono::milliseconds limit) {
    std::unique_lock lock(mutex_);
    std::optional<ReceivedEvent> out;
    changed_.wait_for(lock, limit, [&] {
      std::size_t seen = 0;
      for (const ReceivedEvent& e : events_)
        if (e.type == type && ++seen == n) {
          out = e;
          return true;
        }
      return false;
    });
    return out;
  }
  // Waits until the server ends the stream.
  bool waitEnded(std::chrono::milliseconds limit) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, limit, [&] { return ended_; });
  }
  std::vector<ReceivedEvent> events() const {
    std::lock_guard lock(mutex_);
    return events_;
  }
  int status() const {
    std::lock_guard lock(mutex_);
    return status_;
  }

 private:
  void feed(const std::string& chunk) {
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    buffer_ += chunk;
    for (std::size_t end; (end = buffer_.find("\n\n")) != std::string::npos;) {
      const std::string block = buffer_.substr(0, end);
      buffer_.erase(0, end + 2);
      ReceivedEvent e;
      e.at = now;
      std::string data;
      std::size_t pos = 0;
      while (pos < block.size()) {
        std::size_t nl = block.find('\n', pos);
        if (nl == std::string::npos) nl = block.size();
        const std::string line = block.substr(pos, nl - pos);
        pos = nl + 1;
        if (line.rfind("id: ", 0) == 0) e.id = std::stoull(line.substr(4));
        if (line.rfind("event: ", 0) == 0) e.type = line.substr(7);
        if (line.rfind("data: ", 0) == 0) data += line.substr(6);
      }
      if (e.type.empty()) continue;  // comments, retry
      e.data = nlohmann::json::parse(data, nullptr, false);
      events_.push_back(std::move(e));
    }
    changed_.notify_all();
  }

  httplib::Client client_;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<ReceivedEvent> events_;
  std::string buffer_;
  bool ended_ = false;
  int status_ = 0;
  std::atomic<bool> stop_{false};
};

}  // namespace mdhd::shadow::testing

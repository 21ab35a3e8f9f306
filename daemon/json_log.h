#pragma once
// Structured log: one JSON object per line (requests, job events, service
// events), each with "ts" (UTC, ISO 8601 with milliseconds) and "event".
// Thread-safe; a line is written and flushed whole.
#include <cstdio>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

namespace mdhd::service {

class JsonLog {
 public:
  // `path` empty: stderr. Throws std::runtime_error when the file cannot be opened.
  explicit JsonLog(const std::string& path = "");
  ~JsonLog();
  JsonLog(const JsonLog&) = delete;
  JsonLog& operator=(const JsonLog&) = delete;

  // Writes `fields` with "ts" and "event" put first.
  void write(const std::string& event, const nlohmann::json& fields = nlohmann::json::object());

 private:
  std::mutex mutex_;
  std::FILE* file_ = nullptr;
  bool own_ = false;
};

// Now as "2026-11-22T07:40:01.123Z".
std::string utcTimestamp();

}  // namespace mdhd::service

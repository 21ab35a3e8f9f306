#pragma once
// The events of one shadow for its Server-Sent Events streams: a bounded ring of
// (id, type, JSON text), ids counting from 1, that any number of readers follow
// by id with a bounded wait. A slow reader never holds up the shadow: it finds
// that the events it missed were dropped from the ring.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace mdhd::shadow {

struct ShadowEvent {
  std::uint64_t id = 0;
  std::string type;  // pose, alarm, state
  std::string data;  // one line of JSON
};

class EventLog {
 public:
  explicit EventLog(std::size_t capacity = 1024) : capacity_(capacity) {}

  // Appends an event and wakes the readers; returns its id.
  std::uint64_t publish(std::string type, const nlohmann::json& data);

  // The events after id `after`, waiting up to `wait` while there are none (and
  // the log is open). `missed` (if given) says whether events after `after` had
  // already left the ring.
  std::vector<ShadowEvent> since(std::uint64_t after, std::chrono::milliseconds wait,
                                 bool* missed = nullptr) const;

  std::uint64_t lastId() const;
  // No more events: readers return at once from now on.
  void close();
  bool closed() const;

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::deque<ShadowEvent> ring_;
  std::uint64_t last_ = 0;
  bool closed_ = false;
};

}  // namespace mdhd::shadow

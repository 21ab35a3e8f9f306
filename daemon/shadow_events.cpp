#include "daemon/shadow_events.h"

namespace mdhd::shadow {

std::uint64_t EventLog::publish(std::string type, const nlohmann::json& data) {
  std::string text = data.dump();
  std::uint64_t id = 0;
  {
    std::lock_guard lock(mutex_);
    id = ++last_;
    ring_.push_back({id, std::move(type), std::move(text)});
    while (ring_.size() > capacity_) ring_.pop_front();
  }
  changed_.notify_all();
  return id;
}

std::vector<ShadowEvent> EventLog::since(std::uint64_t after, std::chrono::milliseconds wait,
                                         bool* missed) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, wait, [&] { return closed_ || last_ > after; });
  std::vector<ShadowEvent> out;
  if (missed != nullptr) *missed = !ring_.empty() && ring_.front().id > after + 1;
  for (const ShadowEvent& e : ring_)
    if (e.id > after) out.push_back(e);
  return out;
}

std::uint64_t EventLog::lastId() const {
  std::lock_guard lock(mutex_);
  return last_;
}

void EventLog::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

bool EventLog::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

}  // namespace mdhd::shadow

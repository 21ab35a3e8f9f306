#include "daemon/job_queue.h"

#include <algorithm>

namespace mdhd::service {

bool JobQueue::reserve() {
  if (ids_.size() + reserved_ >= limit_) return false;
  ++reserved_;
  return true;
}

void JobQueue::release() {
  if (reserved_ > 0) --reserved_;
}

void JobQueue::pushReserved(const std::string& id) {
  release();
  ids_.push_back(id);
}

void JobQueue::pushRestored(const std::string& id) {
  ids_.push_back(id);
}

std::optional<std::string> JobQueue::pop() {
  if (ids_.empty()) return std::nullopt;
  std::string id = std::move(ids_.front());
  ids_.pop_front();
  return id;
}

bool JobQueue::remove(const std::string& id) {
  const auto it = std::find(ids_.begin(), ids_.end(), id);
  if (it == ids_.end()) return false;
  ids_.erase(it);
  return true;
}

}  // namespace mdhd::service

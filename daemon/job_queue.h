#pragma once
// The jobs waiting for a worker: first in, first out, bounded. Slots can be
// reserved before the job is committed to the store, so the store's fsync runs
// without holding the queue and a full queue is refused before anything is
// written. Not synchronised: the worker pool guards it.
#include <cstddef>
#include <deque>
#include <optional>
#include <string>

namespace mdhd::service {

class JobQueue {
 public:
  explicit JobQueue(std::size_t limit) : limit_(limit) {}

  // Takes a slot for a job about to be committed; false when full.
  bool reserve();
  // Gives a reserved slot back (the commit failed).
  void release();
  // Fills a reserved slot.
  void pushReserved(const std::string& id);
  // Jobs restored from the store on start: queued whatever the limit.
  void pushRestored(const std::string& id);
  std::optional<std::string> pop();
  // Removes a waiting job; false when it is not waiting.
  bool remove(const std::string& id);

  std::size_t size() const { return ids_.size(); }
  bool empty() const { return ids_.empty(); }
  std::size_t limit() const { return limit_; }

 private:
  std::size_t limit_;
  std::size_t reserved_ = 0;
  std::deque<std::string> ids_;
};

}  // namespace mdhd::service

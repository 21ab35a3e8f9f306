#include "sim/mdh/worker_pool.h"

#include <algorithm>
#include <utility>

namespace mdhd::mdh {

WorkerPool::WorkerPool(int threads) {
  for (int i = 0; i + 1 < threads; ++i) helpers_.emplace_back([this, i] { helperLoop(i); });
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

void WorkerPool::work() {
  for (std::size_t i; !failed_.load(std::memory_order_relaxed) &&
                      (i = next_.fetch_add(1, std::memory_order_relaxed)) < count_;) {
    try {
      (*task_)(i);
    } catch (...) {
      const std::lock_guard lock(mutex_);
      if (!failed_.exchange(true)) error_ = std::current_exception();
    }
  }
}

void WorkerPool::helperLoop(int index) {
  std::uint64_t seen = 0;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || (generation_ != seen && index < active_); });
      if (stop_) return;
      seen = generation_;
    }
    work();
    const std::lock_guard lock(mutex_);
    if (--busy_ == 0) done_.notify_one();
  }
}

void WorkerPool::run(std::size_t count, int workers, const std::function<void(std::size_t)>& task) {
  const int helpers =
      std::clamp(std::min(workers, static_cast<int>(std::min<std::size_t>(count, 1 << 20))) - 1, 0,
                 static_cast<int>(helpers_.size()));
  {
    const std::lock_guard lock(mutex_);
    task_ = &task;
    count_ = count;
    next_.store(0);
    failed_.store(false);
    error_ = nullptr;
    active_ = helpers;
    busy_ = helpers;
    ++generation_;
  }
  if (helpers > 0) wake_.notify_all();
  work();
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_ == 0; });
  task_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace mdhd::mdh

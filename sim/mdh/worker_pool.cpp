#include "sim/mdh/worker_pool.h"

#include <algorithm>
#include <utility>

namespace mdhd::mdh {

WorkerPool::WorkerPool(int threads) {
  for (int i = 0; i + 1 < threads; ++i) helpers_.emplace_back([this, i] { helperLoop(i); });
}

namespace {

// Some tens of microseconds of polling: a pause takes some 40-140 cycles by the
// vendors' figures (not measured here).
constexpr int kSpins = 1000;

inline void pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

}  // namespace

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard lock(mutex_);
    stop_.store(true);
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
    std::uint64_t g = generation_.load(std::memory_order_acquire);
    for (int i = 0; i < kSpins && g == seen && !stop_.load(std::memory_order_relaxed); ++i) {
      pause();
      g = generation_.load(std::memory_order_acquire);
    }
    if (g == seen) {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] {
        return stop_.load() || generation_.load(std::memory_order_acquire) != seen;
      });
      g = generation_.load(std::memory_order_acquire);
    }
    if (stop_.load()) return;
    seen = g;
    if (static_cast<std::uint64_t>(index) >= (g & 0xffu)) continue;  // not asked this time
    work();
    if (busy_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      const std::lock_guard lock(mutex_);  // the caller may be about to sleep on done_
      done_.notify_one();
    }
  }
}

void WorkerPool::run(std::size_t count, int workers, const std::function<void(std::size_t)>& task) {
  const int helpers =
      std::clamp(std::min(workers, static_cast<int>(std::min<std::size_t>(count, 1 << 20))) - 1, 0,
                 std::min(static_cast<int>(helpers_.size()), 255));
  {
    const std::lock_guard lock(mutex_);
    task_ = &task;
    count_ = count;
    next_.store(0);
    failed_.store(false);
    error_ = nullptr;
    busy_.store(helpers);
    const std::uint64_t run = (generation_.load(std::memory_order_relaxed) >> 8) + 1;
    generation_.store(run << 8 | static_cast<std::uint64_t>(helpers), std::memory_order_release);
  }
  if (helpers > 0) wake_.notify_all();
  work();
  for (int i = 0; i < kSpins && busy_.load(std::memory_order_acquire) != 0; ++i) pause();
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_.load(std::memory_order_acquire) == 0; });
  task_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace mdhd::mdh

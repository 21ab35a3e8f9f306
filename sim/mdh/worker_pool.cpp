#include "sim/mdh/worker_pool.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace mdhd::mdh {

WorkerPool::WorkerPool(int threads) {
  for (int i = 0; i + 1 < threads; ++i) helpers_.emplace_back([this, i] { helperLoop(i); });
}

namespace {

inline void pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// How long a thread polls before it sleeps, as a time: a pause lasts 10-140 cycles
// by CPU (24 ns on the EPYC of docs/check.md, where 1000 pauses were too few). The
// program's serial work between two batches (interpreting, building the next
// sweep) takes some 50 us, after which a sleeping helper still has to be woken:
// 25 us of polling left the helper idle 92-105 ms of the dome's 0.5 s cut, 250 us
// 33-43 ms, 500 us and more 33-38 ms.
constexpr std::chrono::microseconds kSpin{500};

// Polls `done()` for up to kSpin; true if it came true.
template <class Done>
bool spinUntil(Done done) {
  const auto until = std::chrono::steady_clock::now() + kSpin;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return true;
      pause();
    }
    if (std::chrono::steady_clock::now() >= until) return done();
  }
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
    std::uint64_t g = seen;
    spinUntil([&] {
      g = generation_.load(std::memory_order_acquire);
      return g != seen || stop_.load(std::memory_order_relaxed);
    });
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
  spinUntil([&] { return busy_.load(std::memory_order_acquire) == 0; });
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_.load(std::memory_order_acquire) == 0; });
  task_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace mdhd::mdh

#pragma once
// A few threads kept for the life of a stock, so that cutting a step on two
// cores costs a wake-up instead of a thread start (tens of microseconds). A
// helper that has finished polls for the next run for a while (kSpin, 500 us)
// before it sleeps, and so does the caller waiting for the helpers: the steps
// of a program follow each other closely, and a sleeping thread needs a system
// call and a reschedule to wake (polling: -7 % wall on the dome at 2 threads;
// polling by time instead of 1000 pauses: -5 %, docs/check.md).
// run() hands out the indices 0..count-1 to the caller and the helpers through
// one atomic counter and returns when all are done; which thread runs which
// index does not matter to the callers (they merge results in index order).
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace mdhd::mdh {

class WorkerPool {
 public:
  // threads >= 1: the caller plus threads - 1 helpers.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(helpers_.size()) + 1; }
  // Runs task(i) for every i < count on up to `workers` threads (the caller
  // included). The first exception stops the handing out and is rethrown here.
  void run(std::size_t count, int workers, const std::function<void(std::size_t)>& task);

 private:
  void helperLoop(int index);
  void work();

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> helpers_;
  // Written by run() before it publishes a new generation (release), read by the
  // helpers after they see it (acquire).
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::size_t count_ = 0;
  std::atomic<std::size_t> next_{0};
  std::atomic<bool> failed_{false};
  std::exception_ptr error_;  // under mutex_
  // The run's number << 8 | how many helpers it asks for (at most 255): one word,
  // so a helper never pairs one run's number with another run's count.
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<int> busy_{0};  // helpers asked for this run and still working
  std::atomic<bool> stop_{false};
};

}  // namespace mdhd::mdh

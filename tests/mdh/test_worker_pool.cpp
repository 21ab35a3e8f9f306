// The stock's persistent worker pool: every index runs exactly once per run,
// runs can follow each other any number of times, a task's exception comes
// back to the caller and the pool stays usable.
#include "sim/mdh/worker_pool.h"

#include <atomic>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace mdhd::mdh {
namespace {

TEST(WorkerPool, EveryIndexRunsExactlyOnceOnAsManyThreadsAsAsked) {
  WorkerPool pool(3);
  EXPECT_EQ(pool.threads(), 3);
  for (int run = 0; run < 200; ++run) {
    const std::size_t n = 1 + run % 37;
    std::vector<std::atomic<int>> hits(n);
    std::mutex m;
    std::set<std::thread::id> threads;
    pool.run(n, 1 + run % 3, [&](std::size_t i) {
      hits[i].fetch_add(1);
      const std::lock_guard lock(m);
      threads.insert(std::this_thread::get_id());
    });
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "run " << run;
    EXPECT_LE(threads.size(), static_cast<std::size_t>(1 + run % 3));
    if (run % 3 == 0) {
      EXPECT_EQ(threads.size(), 1u);  // one worker: the caller alone
      EXPECT_EQ(*threads.begin(), std::this_thread::get_id());
    }
  }
}

// Runs that ask for no helper return at once, so the next run can start while a
// helper is still looking at the last one: it must not take the new run's
// count of helpers for the old run's (that lost a helper and hung the caller).
TEST(WorkerPool, BackToBackRunsOfOneAndThreeWorkers) {
  WorkerPool pool(3);
  std::atomic<long> total{0};
  long expected = 0;
  for (int run = 0; run < 50000; ++run) {
    const std::size_t n = run % 2 == 0 ? 1 : 4;
    pool.run(n, run % 2 == 0 ? 1 : 3, [&](std::size_t) { total.fetch_add(1); });
    expected += static_cast<long>(n);
  }
  EXPECT_EQ(total.load(), expected);
}

TEST(WorkerPool, AnExceptionReachesTheCallerAndThePoolGoesOn) {
  WorkerPool pool(2);
  for (int workers : {1, 2}) {
    std::atomic<int> ran{0};
    EXPECT_THROW(pool.run(100, workers,
                          [&](std::size_t i) {
                            ++ran;
                            if (i == 5) throw std::runtime_error("task 5");
                          }),
                 std::runtime_error);
    if (workers == 1) {
      EXPECT_EQ(ran.load(), 6);  // the handing out stopped at the throw
    }
    std::atomic<int> after{0};
    pool.run(50, 2, [&](std::size_t) { ++after; });
    EXPECT_EQ(after.load(), 50);
  }
}

TEST(WorkerPool, ZeroTasksAndOneThread) {
  WorkerPool one(1);
  int count = 0;
  one.run(0, 4, [&](std::size_t) { ++count; });
  EXPECT_EQ(count, 0);
  one.run(10, 4, [&](std::size_t) { ++count; });  // no helpers: all on the caller
  EXPECT_EQ(count, 10);
}

}  // namespace
}  // namespace mdhd::mdh

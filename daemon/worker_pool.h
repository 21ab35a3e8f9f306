#pragma once
// The simulation workers: take queued jobs first in first out, run them through
// runServiceJob, keep their progress, and stop them on request (DELETE), past
// the run-time limit, or at shutdown (requeued, never lost). The store holds the
// truth; this holds only what is in flight.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "daemon/job_queue.h"
#include "daemon/job_store.h"
#include "daemon/json_log.h"
#include "daemon/metrics.h"

namespace mdhd::service {

struct WorkerSettings {
  int workers = 1;
  std::size_t queue_limit = 64;
  double max_job_seconds = 3600.0;
  int max_interruptions = 3;         // a job the process died under this often fails
  std::uint64_t max_mesh_bytes = 0;  // a larger final stock is not written (0: no limit)
};

class WorkerPool {
 public:
  WorkerPool(WorkerSettings settings, JobStore& store, Metrics& metrics, JsonLog& log);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Queues the jobs the store says are waiting, then starts the workers.
  void start();

  enum class Submitted { kQueued, kQueueFull, kStopping };
  // Takes a queue slot, runs `commit` (which stores the job) outside the lock,
  // then queues `id`. A full queue or a stopping pool commits nothing.
  Submitted submit(const std::string& id, const std::function<void()>& commit);

  enum class Cancelled { kNotActive, kRemovedFromQueue, kStopped, kStillStopping };
  // Cancels a waiting job, or stops a running one and waits up to `wait` for it.
  Cancelled cancel(const std::string& id, std::chrono::milliseconds wait);

  // Progress 0..1 of a running job.
  std::optional<double> progress(const std::string& id) const;
  std::size_t queued() const;
  std::size_t running() const;
  bool queueFull() const;

  // No new jobs; running ones get `grace` to finish, then are stopped and
  // requeued. Joins every thread. Idempotent.
  void stop(std::chrono::milliseconds grace);

 private:
  enum class StopReason { kNone, kUser, kTimeLimit, kShutdown };
  struct Running {
    std::atomic<bool> cancel{false};
    std::atomic<double> progress{0.0};
    StopReason reason = StopReason::kNone;
    std::chrono::steady_clock::time_point deadline;
  };

  void workerLoop();
  void watchdogLoop();
  void runOne(const std::string& id, Running& running);

  WorkerSettings settings_;
  JobStore& store_;
  Metrics& metrics_;
  JsonLog& log_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;      // workers: a job or stop
  std::condition_variable finished_;  // a running job left
  JobQueue queue_;
  std::map<std::string, std::shared_ptr<Running>> running_;
  bool stopping_ = false;
  bool started_ = false;
  std::vector<std::thread> threads_;
  std::thread watchdog_;
};

}  // namespace mdhd::service

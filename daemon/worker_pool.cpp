#include "daemon/worker_pool.h"

#include "daemon/service_job.h"
#include "sim/check/simulation.h"

namespace mdhd::service {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

WorkerPool::WorkerPool(WorkerSettings settings, JobStore& store, Metrics& metrics, JsonLog& log)
    : settings_(settings),
      store_(store),
      metrics_(metrics),
      log_(log),
      queue_(settings.queue_limit) {}

WorkerPool::~WorkerPool() {
  stop(std::chrono::milliseconds(0));
}

void WorkerPool::start() {
  const std::vector<std::string> waiting = store_.recoverQueued(
      settings_.max_interruptions, errorReportText("the service stopped while running this job " +
                                                       std::to_string(settings_.max_interruptions) +
                                                       " times; it is not run again",
                                                   "(limits)"));
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const std::string& id : waiting) queue_.pushRestored(id);
    started_ = true;
  }
  if (!waiting.empty()) log_.write("jobs_restored", {{"queued", waiting.size()}});
  for (int i = 0; i < settings_.workers; ++i) threads_.emplace_back([this] { workerLoop(); });
  watchdog_ = std::thread([this] { watchdogLoop(); });
}

WorkerPool::Submitted WorkerPool::submit(const std::string& id,
                                         const std::function<void()>& commit) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) return Submitted::kStopping;
    if (!queue_.reserve()) return Submitted::kQueueFull;
  }
  try {
    commit();
  } catch (...) {
    const std::lock_guard<std::mutex> lock(mutex_);
    queue_.release();
    throw;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    queue_.pushReserved(id);
  }
  wake_.notify_one();
  return Submitted::kQueued;
}

WorkerPool::Cancelled WorkerPool::cancel(const std::string& id, std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (queue_.remove(id)) {
    store_.finishJob(id, "cancelled", std::nullopt, false);
    return Cancelled::kRemovedFromQueue;
  }
  const auto it = running_.find(id);
  if (it == running_.end()) return Cancelled::kNotActive;
  it->second->reason = StopReason::kUser;
  it->second->cancel = true;
  const bool gone =
      finished_.wait_for(lock, wait, [&] { return running_.find(id) == running_.end(); });
  return gone ? Cancelled::kStopped : Cancelled::kStillStopping;
}

std::optional<double> WorkerPool::progress(const std::string& id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = running_.find(id);
  if (it == running_.end()) return std::nullopt;
  return it->second->progress.load(std::memory_order_relaxed);
}

std::size_t WorkerPool::queued() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

std::size_t WorkerPool::running() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return running_.size();
}

bool WorkerPool::queueFull() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size() >= queue_.limit();
}

void WorkerPool::stop(std::chrono::milliseconds grace) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (stopping_) return;
    stopping_ = true;
    wake_.notify_all();
    finished_.wait_for(lock, grace, [&] { return running_.empty(); });
    for (auto& [id, run] : running_) {
      run->reason = StopReason::kShutdown;
      run->cancel = true;
    }
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
  threads_.clear();
  if (watchdog_.joinable()) watchdog_.join();
}

void WorkerPool::workerLoop() {
  for (;;) {
    std::string id;
    std::shared_ptr<Running> run;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      id = *queue_.pop();
      run = std::make_shared<Running>();
      run->deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(settings_.max_job_seconds));
      running_[id] = run;
    }
    runOne(id, *run);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      running_.erase(id);
    }
    finished_.notify_all();
  }
}

void WorkerPool::runOne(const std::string& id, Running& run) {
  const Clock::time_point started = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - started).count(); };
  std::optional<JobRecord> record;
  try {
    store_.markRunning(id);
    record = store_.job(id, true);
  } catch (const std::exception& e) {
    log_.write("job_store_error", {{"id", id}, {"what", e.what()}});
    return;  // still queued or running in the store: the next start runs it
  }
  if (!record) return;  // deleted meanwhile
  log_.write("job_started", {{"id", id}, {"attempt", record->attempts}});
  std::int64_t moves = 0;
  cli::CheckControls controls;
  controls.cancel = &run.cancel;
  controls.progress = [&run, &moves](double fraction, std::int64_t n) {
    run.progress.store(fraction, std::memory_order_relaxed);
    moves = n;
  };
  std::string outcome;
  try {
    try {
      JobOutcome out =
          runServiceJob(record->job, store_.meshPath(id), controls, settings_.max_mesh_bytes);
      std::string meshError;
      if (!out.mesh_error.empty()) {
        log_.write("job_mesh_error",
                   {{"id", id}, {"code", out.mesh_error_code}, {"what", out.mesh_error}});
        meshError =
            nlohmann::json{{"code", out.mesh_error_code}, {"message", out.mesh_error}}.dump();
      }
      store_.finishJob(id, out.status, out.report, out.mesh, meshError);
      outcome = out.status;
      moves = out.moves;
    } catch (const check::Cancelled&) {
      StopReason reason;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        reason = run.reason;
      }
      if (reason == StopReason::kShutdown) {
        store_.requeue(id);
        outcome = "requeued";
      } else if (reason == StopReason::kTimeLimit) {
        store_.finishJob(id, "failed",
                         errorReportText("the job ran longer than the limit of " +
                                             std::to_string(settings_.max_job_seconds) + " s",
                                         "(limits)"),
                         false);
        outcome = "failed";
      } else {
        store_.finishJob(id, "cancelled", std::nullopt, false);
        outcome = "cancelled";
      }
    }
  } catch (const std::exception& e) {
    // The store failed: leave the job as the store has it; a restart runs it again.
    log_.write("job_store_error", {{"id", id}, {"what", e.what()}});
    outcome = "error";
  }
  const double s = seconds();
  metrics_.jobFinished(outcome, s, moves);
  log_.write("job_finished", {{"id", id}, {"status", outcome}, {"seconds", s}, {"moves", moves}});
}

void WorkerPool::watchdogLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!(stopping_ && running_.empty())) {
    const Clock::time_point now = Clock::now();
    for (auto& [id, run] : running_) {
      if (run->reason == StopReason::kNone && now > run->deadline) {
        run->reason = StopReason::kTimeLimit;
        run->cancel = true;
        log_.write("job_time_limit", {{"id", id}});
      }
    }
    finished_.wait_for(lock, std::chrono::milliseconds(50));
  }
}

}  // namespace mdhd::service

#include "daemon/service.h"

#include <algorithm>
#include <stdexcept>

#include "daemon/openapi_parts.h"
#include "daemon/routes_jobs.h"
#include "daemon/routes_machines.h"
#include "daemon/routes_ops.h"
#include "daemon/routes_shadows.h"
#include "daemon/routes_web.h"
#include "protocol/json_schema.h"

namespace mdhd::service {
namespace {

ServiceConfig checked(ServiceConfig config) {
  const std::string problem = configProblem(config);
  if (!problem.empty()) throw std::runtime_error(problem);
  return config;
}

HttpSettings httpSettings(const ServiceConfig& c) {
  return {c.bind, c.port, c.tokens, c.http_threads, c.max_body_bytes};
}

WorkerSettings workerSettings(const ServiceConfig& c) {
  return {effectiveWorkers(c), c.queue_limit, c.max_job_seconds, c.max_interruptions,
          c.max_mesh_mb << 20};
}

void addContractSchemas(HttpService& http) {
  http.addSchema("Error", errorSchema());
  const nlohmann::json job = schemaComponents("Job", "Job_", protocol::jobSchema().document());
  const nlohmann::json report =
      schemaComponents("Report", "Report_", protocol::reportSchema().document());
  for (const nlohmann::json* part : {&job, &report}) {
    for (const auto& [name, schema] : part->items()) http.addSchema(name, schema);
  }
}

}  // namespace

Service::Service(ServiceConfig config)
    : config_(checked(std::move(config))),
      log_(std::make_unique<JsonLog>(config_.log_file)),
      store_(std::make_unique<JobStore>(config_.data_dir)),
      pool_(std::make_unique<WorkerPool>(workerSettings(config_), *store_, metrics_, *log_)),
      // Each open event stream holds an HTTP thread: streams get at most half of them.
      shadows_(std::make_unique<shadow::ShadowRegistry>(
          kMaxShadows, static_cast<std::size_t>(std::max(1, config_.http_threads / 2)))),
      http_(httpSettings(config_), *log_, metrics_) {
  if (config_.example_machines) registerExampleMachines(*store_);
  addContractSchemas(http_);
  addOpsRoutes(http_, metrics_, [this] { return unready(); });
  addJobRoutes(http_, *store_, *pool_, config_);
  addMachineRoutes(http_, *store_);
  addShadowRoutes(http_, *shadows_, *store_, config_);
  addWebRoutes(http_);
  metrics_.addGauge("mdhd_shadows_running", "Live shadows polling a machine.",
                    [this] { return static_cast<double>(shadows_->running()); });
  metrics_.addGauge("mdhd_shadow_streams", "Open shadow event streams.",
                    [this] { return static_cast<double>(shadows_->streams()); });
  metrics_.addGauge("mdhd_jobs_queued", "Jobs waiting for a worker.",
                    [this] { return static_cast<double>(pool_->queued()); });
  metrics_.addGauge("mdhd_jobs_running", "Jobs on a worker now.",
                    [this] { return static_cast<double>(pool_->running()); });
  metrics_.addGauge("mdhd_queue_limit", "Jobs that may wait before submissions get 429.",
                    [this] { return static_cast<double>(config_.queue_limit); });
  metrics_.addGauge("mdhd_workers", "Simulation workers.",
                    [this] { return static_cast<double>(effectiveWorkers(config_)); });
}

Service::~Service() {
  stop();
}

std::string Service::unready() const {
  if (stopping_) return "the service is shutting down";
  if (pool_->queueFull()) return "the job queue is full";
  return "";
}

void Service::start() {
  pool_->start();
  http_.start();
  started_ = true;
  log_->write("service_started", {{"bind", config_.bind},
                                  {"port", http_.port()},
                                  {"data_dir", config_.data_dir},
                                  {"workers", effectiveWorkers(config_)},
                                  {"auth", !config_.tokens.empty()}});
}

void Service::stop() {
  if (stopping_.exchange(true)) return;
  // Shadows first (their event streams end, so none holds an HTTP thread), then
  // requests (nothing new is accepted), then the jobs in flight.
  shadows_->stopAll();
  http_.stop();
  const auto grace =
      std::chrono::milliseconds(static_cast<std::int64_t>(config_.shutdown_grace_seconds * 1000.0));
  pool_->stop(grace);
  if (started_) log_->write("service_stopped");
}

}  // namespace mdhd::service

#pragma once
// `mdhd serve` as one object: the log, metrics, durable store, worker pool and
// HTTP front with every route group over them. cli_serve runs it until a
// signal; tests run it in-process on port 0. More route groups (shadows) take
// the same HttpService, Metrics, JsonLog and JobStore: add them in the
// constructor beside addJobRoutes.
#include <atomic>
#include <memory>
#include <string>

#include "daemon/http_service.h"
#include "daemon/job_store.h"
#include "daemon/json_log.h"
#include "daemon/metrics.h"
#include "daemon/service_config.h"
#include "daemon/shadow_registry.h"
#include "daemon/worker_pool.h"

namespace mdhd::service {

class Service {
 public:
  // Opens the store (creating the data folder). Throws std::runtime_error (with
  // what is wrong) for an unusable configuration or store.
  explicit Service(ServiceConfig config);
  ~Service();
  Service(const Service&) = delete;
  Service& operator=(const Service&) = delete;

  // Requeues what a previous run left, starts the workers and serves. Throws
  // std::runtime_error when the address cannot be bound.
  void start();
  // Graceful stop: no new requests, running jobs get the grace period, then are
  // stopped and requeued. Idempotent.
  void stop();

  int port() const { return http_.port(); }
  const ServiceConfig& config() const { return config_; }
  HttpService& http() { return http_; }
  Metrics& metrics() { return metrics_; }
  JsonLog& log() { return *log_; }
  JobStore& store() { return *store_; }
  WorkerPool& workers() { return *pool_; }
  shadow::ShadowRegistry& shadows() { return *shadows_; }

 private:
  std::string unready() const;

  ServiceConfig config_;
  std::unique_ptr<JsonLog> log_;
  Metrics metrics_;
  std::unique_ptr<JobStore> store_;
  std::unique_ptr<WorkerPool> pool_;
  std::unique_ptr<shadow::ShadowRegistry> shadows_;
  HttpService http_;
  std::atomic<bool> stopping_{false};
  bool started_ = false;
};

}  // namespace mdhd::service

#pragma once
// /api/v1/jobs: submit (POST), list (GET, paged), status and report (GET {id}),
// the final stock as STL (GET {id}/mesh), cancel or delete (DELETE {id}).
#include "daemon/http_service.h"
#include "daemon/job_store.h"
#include "daemon/service_config.h"
#include "daemon/worker_pool.h"

namespace mdhd::service {

void addJobRoutes(HttpService& http, JobStore& store, WorkerPool& pool,
                  const ServiceConfig& config);

}  // namespace mdhd::service

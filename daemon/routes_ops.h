#pragma once
// Operations routes: GET /healthz, GET /metrics (Prometheus text), GET /openapi.json.
#include <functional>
#include <string>

#include "daemon/http_service.h"

namespace mdhd::service {

// `unready` returns "" when the service can take work, else why not (503).
void addOpsRoutes(HttpService& http, Metrics& metrics, std::function<std::string()> unready);

}  // namespace mdhd::service

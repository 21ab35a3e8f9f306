#include "daemon/routes_ops.h"

#include <httplib.h>

#include "daemon/http_errors.h"
#include "daemon/openapi_parts.h"

namespace mdhd::service {

void addOpsRoutes(HttpService& http, Metrics& metrics, std::function<std::string()> unready) {
  http.route({"GET",
              "/healthz",
              {{"summary", "Whether the service can take work"},
               {"tags", {"operations"}},
               {"responses",
                {{"200", jsonResponse("It can.", {{"type", "object"}})},
                 {"503", errorResponse("It cannot (shutting down, queue full, store failing).")}}}},
              false},
             [unready](const httplib::Request&, httplib::Response& res) {
               const std::string why = unready();
               if (!why.empty()) {
                 // When to ask again, as a full queue's 429 says it: load balancers and
                 // clients back off instead of hammering.
                 res.set_header("Retry-After", "5");
                 throw HttpError(503, "unavailable", why);
               }
               sendJson(res, 200, {{"status", "ok"}});
             });
  http.route({"GET",
              "/metrics",
              {{"summary", "Prometheus metrics (text exposition format 0.0.4)"},
               {"tags", {"operations"}},
               {"responses",
                {{"200",
                  {{"description", "The metrics."},
                   {"content", {{"text/plain", {{"schema", {{"type", "string"}}}}}}}}}}}}},
             [&metrics](const httplib::Request&, httplib::Response& res) {
               res.status = 200;
               res.set_content(metrics.render(), "text/plain; version=0.0.4; charset=utf-8");
             });
  http.route({"GET",
              "/openapi.json",
              {{"summary", "This document"},
               {"tags", {"operations"}},
               {"responses", {{"200", jsonResponse("OpenAPI 3.1.", {{"type", "object"}})}}}},
              false},
             [&http](const httplib::Request&, httplib::Response& res) {
               sendJson(res, 200, http.openApi());
             });
}

}  // namespace mdhd::service

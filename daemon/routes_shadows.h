#pragma once
// /api/v1/shadows: live shadowing of a machine over Modbus TCP (service.md,
// "Live shadowing"): POST starts one (201 {id}), GET its state, /events its
// Server-Sent Events (pose, alarm, state), /mesh the live stock as STL, DELETE
// stops it (and deletes a stopped one).
#include "daemon/http_service.h"
#include "daemon/job_store.h"
#include "daemon/service_config.h"
#include "daemon/shadow_registry.h"

namespace mdhd::service {

// At most this many shadows run at once; more get 429.
inline constexpr std::size_t kMaxShadows = 8;

void addShadowRoutes(HttpService& http, shadow::ShadowRegistry& shadows, JobStore& store,
                     const ServiceConfig& config);

}  // namespace mdhd::service

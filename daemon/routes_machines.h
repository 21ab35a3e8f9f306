#pragma once
// /api/v1/machines: a registry of machine kinematics that jobs name by
// `"machine": "<name>"`. PUT (create or replace), GET, DELETE, and the list.
#include "daemon/http_service.h"
#include "daemon/job_store.h"

namespace mdhd::service {

void addMachineRoutes(HttpService& http, JobStore& store);

// On the first start only (a flag in the store): the preset machines of
// sim/kinematics/presets, under the names docs/daemon.md lists.
void registerExampleMachines(JobStore& store);

}  // namespace mdhd::service

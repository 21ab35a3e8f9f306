#pragma once
// check::Report <-> the report document of the contract (job-format.md section 5,
// protocol/schemas/report.schema.json). Joints are named as the machine names them.
#include <nlohmann/json.hpp>

#include "sim/check/report.h"
#include "sim/kinematics/machine.h"

namespace mdhd::protocol {

// `machine` names the joints of collision entries; null: by axis letter, X Y Z
// always and the others when non-zero.
nlohmann::json reportToJson(const check::Report& report, const kin::Machine* machine);

// One entry of the report's `collisions` (a live shadow's alarms use it too).
nlohmann::json collisionToJson(const check::Collision& collision, const kin::Machine* machine);

// Joint values by the machine's joint names (see reportToJson for null).
nlohmann::json jointsToJson(const gcode::AxisValues& q, const kin::Machine* machine);

}  // namespace mdhd::protocol

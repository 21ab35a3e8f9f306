#pragma once
// The machine object of the job format (spec section 2) <-> kin::Machine. Strict:
// every field's type is checked and unknown fields are errors, so a typo cannot
// pass silently; each error names the field's path in the job document.
#include <string>

#include <nlohmann/json.hpp>

#include "protocol/json_fields.h"
#include "sim/kinematics/machine.h"

namespace mdhd::protocol {

// Errors are the protocol's FieldError (field() is the path, e.g.
// "machine.joints[3].axis"); the alias names them for this codec's readers.
using MachineJsonError = FieldError;

// Reads and validates a machine; `path` is where it sits in the document (for
// messages). Throws FieldError. Required: joints, tool_chain, workpiece_chain,
// spindle_axis, rapid_feed, max_feed; optional: name, home, and per joint origin and
// limits.
kin::Machine machineFromJson(const nlohmann::json& j, const std::string& path = "machine");

// The machine as the job format writes it (origin only where it is non-zero or the
// joint is rotary; home for every joint).
nlohmann::json machineToJson(const kin::Machine& machine);

}  // namespace mdhd::protocol

#pragma once
// The machine object of the job format (spec section 2) <-> kin::Machine. Strict:
// every field's type is checked and unknown fields are errors, so a typo cannot
// pass silently; each error names the field's path in the job document.
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "sim/kinematics/machine.h"

namespace mdhd::protocol {

class MachineJsonError : public std::runtime_error {
 public:
  MachineJsonError(std::string field, const std::string& message)
      : std::runtime_error(field + ": " + message), field_(std::move(field)) {}
  // The path of the offending field, e.g. "machine.joints[3].axis".
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// Reads and validates a machine; `path` is where it sits in the document (for
// messages). Throws MachineJsonError. Required: joints, tool_chain, workpiece_chain,
// spindle_axis, rapid_feed, max_feed; optional: name, home, and per joint origin and
// limits.
kin::Machine machineFromJson(const nlohmann::json& j, const std::string& path = "machine");

// The machine as the job format writes it (origin only where it is non-zero or the
// joint is rotary; home for every joint).
nlohmann::json machineToJson(const kin::Machine& machine);

}  // namespace mdhd::protocol

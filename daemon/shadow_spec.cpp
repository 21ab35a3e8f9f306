#include "daemon/shadow_spec.h"

#include "protocol/job_json.h"
#include "protocol/modbus_map_json.h"

namespace mdhd::shadow {

using protocol::FieldError;

ShadowSpec shadowSpecFromJson(const nlohmann::json& body, const MachineLookup& lookup) {
  ShadowSpec spec;
  spec.job = protocol::jobFromJson(body, protocol::ProgramRequirement::kOptional);
  protocol::Job& job = spec.job;
  if (!job.machine_file.empty())
    throw FieldError("machine_file", "not accepted over HTTP: give machine (an object or a name)");
  if (!job.program_file.empty())
    throw FieldError("program_file", "not accepted over HTTP: give the program text");
  if (!job.machine_name.empty()) {
    std::optional<kin::Machine> machine = lookup ? lookup(job.machine_name) : std::nullopt;
    if (!machine)
      throw FieldError("machine", "no registered machine named '" + job.machine_name + "'");
    job.machine = std::move(*machine);
  }
  if (!job.modbus) throw FieldError("modbus", "missing (the register map to poll)");
  spec.map = protocol::modbusMapFromJson(*job.modbus, "modbus", &*job.machine);
  return spec;
}

}  // namespace mdhd::shadow

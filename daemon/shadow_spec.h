#pragma once
// What a shadow is asked to mirror (service.md, "Live shadowing over Modbus TCP"):
// the cell as job fields (machine, tools, stock, fixtures, work_offsets, options,
// optionally the program the machine runs) and the `modbus` register map.
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "protocol/job.h"
#include "protocol/modbus_map.h"

namespace mdhd::shadow {

struct ShadowSpec {
  protocol::Job job;  // job.machine is set; job.program may be absent
  protocol::ModbusMap map;
};

// A registered machine by name, or nullopt when there is none of that name.
using MachineLookup = std::function<std::optional<kin::Machine>(const std::string& name)>;

// Reads a POST /api/v1/shadows body with the job codec (program optional) and the
// strict register map against the machine. File fields (machine_file,
// program_file) are refused: a request never names a path. Throws
// protocol::FieldError naming the field.
ShadowSpec shadowSpecFromJson(const nlohmann::json& body, const MachineLookup& lookup = {});

}  // namespace mdhd::shadow

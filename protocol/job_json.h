#pragma once
// The job document <-> protocol::Job. Strict: types, ranges and unknown fields are
// errors (FieldError naming the field), so a typo never passes silently.
#include <string_view>

#include <nlohmann/json.hpp>

#include "protocol/job.h"
#include "protocol/json_fields.h"

namespace mdhd::protocol {

enum class ProgramRequirement { kRequired, kOptional };

// Reads a job. machine_file / program_file stay paths: the caller resolves them.
Job jobFromJson(const nlohmann::json& j,
                ProgramRequirement program = ProgramRequirement::kRequired);

// Parses JSON text; a syntax error becomes a FieldError at "(document)" whose
// message gives the line and column.
nlohmann::json parseJsonText(std::string_view text);

}  // namespace mdhd::protocol

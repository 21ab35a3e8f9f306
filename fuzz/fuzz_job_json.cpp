// libFuzzer target for the job document (job-format.md): any bytes either fail with a
// FieldError naming the field (not JSON, the schema, the strict codec), or give a job
// that the schema accepted too, whose machine builds and whose every tool's cutter,
// shank and holder build or are refused with std::invalid_argument.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <stdexcept>

#include "fuzz/json_input.h"
#include "protocol/job_json.h"
#include "protocol/json_schema.h"
#include "sim/geometry/tool_part.h"
#include "sim/kinematics/kinematics.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mdhd;
  const std::optional<nlohmann::json> input = fuzz::jsonInput(data, size);
  if (!input) return 0;
  const nlohmann::json& doc = *input;
  const bool schemaAccepts = protocol::jobSchema().validate(doc).empty();
  protocol::Job job;
  try {
    // As a job is read (the schema requires program or program_file); shadows, which
    // may go without a program, have a schema of their own.
    job = protocol::jobFromJson(doc, protocol::ProgramRequirement::kRequired);
  } catch (const protocol::FieldError&) {
    return 0;
  }
  // The schema is the contract the codec implements: what the codec takes, it allows.
  if (!schemaAccepts) std::abort();
  if (job.machine) {
    const kin::Kinematics kin(*job.machine);  // a machine the codec accepts must build
    (void)kin;
  }
  for (const geom::Tool& tool : job.tools)
    for (geom::ToolPartKind kind :
         {geom::ToolPartKind::kCutter, geom::ToolPartKind::kShank, geom::ToolPartKind::kHolder}) {
      try {
        const geom::ToolPart part = geom::makeToolPart(tool, kind);
        (void)part;
      } catch (const std::invalid_argument&) {
      }
    }
  return 0;
}

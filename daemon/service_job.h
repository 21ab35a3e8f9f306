#pragma once
// What the service does with a job: checks the document on acceptance (schema,
// strict codec, limits, and a dry interpretation so a program that does not
// interpret is refused with its line and column), and runs an accepted one on a
// worker exactly as `mdhd check` does (same runner, report and STL bytes).
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "daemon/check_runner.h"

namespace mdhd::service {

struct AcceptedJob {
  nlohmann::json doc;        // the job with the machine inlined: what is stored
  std::string machine_name;  // when the job named a registered machine
};

// How long acceptJob interprets a program before it takes it on what it has read:
// the request must not wait for a program of a hundred million pecks (its run is
// bounded by max_job_seconds, and reports a later error itself).
inline constexpr std::chrono::milliseconds kDryInterpretBudget{5000};

// Checks a posted job. `lookupMachine` returns a registered machine's JSON or
// nullopt. Throws HttpError: 400 (field, with "field"), 413 (program too long),
// 422 (program does not interpret, with "line", "column", "block").
AcceptedJob acceptJob(
    nlohmann::json doc, std::size_t maxProgramBytes,
    const std::function<std::optional<nlohmann::json>(const std::string&)>& lookupMachine,
    std::chrono::milliseconds interpretBudget = kDryInterpretBudget);

struct JobOutcome {
  std::string status;  // done (clean or collisions) or failed (report status error)
  std::string report;  // the report JSON text
  bool mesh = false;   // the final stock was written
  std::string mesh_error;
  std::string mesh_error_code;  // mesh_too_large or mesh_write_failed, with mesh_error
  std::int64_t moves = 0;
};

// Runs a stored job; the final stock goes to `meshPath`, unless its STL would be
// larger than `maxMeshBytes` (0: no limit): the job is then done without a mesh
// (mesh_error_code mesh_too_large). Throws check::Cancelled when controls.cancel is
// raised, while meshing too.
JobOutcome runServiceJob(const std::string& jobJson, const std::filesystem::path& meshPath,
                         cli::CheckControls controls, std::uint64_t maxMeshBytes = 0);

// A report document (status error) for a job that never produced one.
std::string errorReportText(const std::string& message, const std::string& field);

}  // namespace mdhd::service

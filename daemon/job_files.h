#pragma once
// Jobs given on the command line: the job file, and the machine_file and
// program_file it names, resolved relative to the job file's folder.
#include <filesystem>
#include <memory>
#include <string>

#include "protocol/job.h"
#include "sim/gcode/interpreter_config.h"
#include "sim/gcode/source.h"

namespace mdhd::cli {

struct LoadedJob {
  protocol::Job job;                   // job.machine is always set after loading
  std::filesystem::path base_dir;      // the job file's folder; empty: a job without files
  std::filesystem::path program_path;  // empty when the program is inline
};

// Reads and validates a job file. Throws protocol::FieldError (field and what is
// wrong; file problems as field "machine_file"/"program_file"/"(file)").
LoadedJob loadJobFile(const std::filesystem::path& path);

// The program as a streaming line source (a file is never read whole).
std::unique_ptr<gcode::LineSource> openProgram(const LoadedJob& loaded);

// Interpreter set-up for a job: work offsets, the machine's home and axis letters,
// the tool table from the job's tools, and o<name> call files from the program's
// folder (names with path separators are refused; none without a folder).
gcode::InterpreterConfig interpreterConfig(const LoadedJob& loaded);

}  // namespace mdhd::cli

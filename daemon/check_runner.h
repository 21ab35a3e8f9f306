#pragma once
// One check of a job, end to end and without the command line's I/O: the job
// (validated against the job schema, then the strict codec), the interpreter
// driving a check::Simulation, and every failure turned into a report with
// status "error" that says what and where. The CLI and the service share it.
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>

#include "daemon/job_files.h"
#include "sim/check/report.h"
#include "sim/check/simulation.h"

namespace mdhd::cli {

struct CheckControls {
  // Called after each motion: fraction of the program's lines done, motions so far.
  std::function<void(double fraction, std::int64_t moves)> progress;
  const std::atomic<bool>* cancel = nullptr;  // raise to stop within a step
  // Called with the final stock of a run that completed (meshing).
  std::function<void(const mdh::Stock&)> finished;
  // Threads cutting the stock and meshing it. Results are bit-identical for any count;
  // the command line uses the machine's cores, the service 1 (it runs one job per core
  // already).
  int threads = 1;
  // Feed steps cut at once (check::SimulationOptions::batch_steps); 0: its default.
  int batch_steps = 0;
};

// The job's fixtures as solids for the simulation.
std::vector<std::unique_ptr<geom::LineSolid>> fixtureSolids(const protocol::Job& job);

// The simulation's options from the job's.
check::SimulationOptions simulationOptions(const protocol::JobOptions& options);

// Throws protocol::FieldError at `options.density` when the engine cannot hold the
// job's stock at its density (check::Simulation::stockProblem): a service refuses
// such a job when it is submitted, not when it runs.
void requireStockFits(const protocol::Job& job);

// Loads a job file: the JSON schema first (errors name the JSON path), then the
// strict codec and the machine and program files. Throws protocol::FieldError.
LoadedJob loadCheckedJobFile(const std::filesystem::path& path);

// Runs a loaded job. Program and motion errors come back as a report with status
// error and the place (line, column, block text); check::Cancelled is rethrown.
check::Report runCheckJob(const LoadedJob& loaded, const CheckControls& controls = {});

// A report that only says why the job could not be used.
check::Report errorReport(check::ReportError error);

// Text of line `line` (1-based) of the job's main program, or "" (read streaming).
std::string programLine(const LoadedJob& loaded, int line);

}  // namespace mdhd::cli

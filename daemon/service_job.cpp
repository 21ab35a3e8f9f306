#include "daemon/service_job.h"

#include <chrono>

#include "daemon/http_errors.h"
#include "daemon/job_store.h"
#include "daemon/stock_stl.h"
#include "protocol/job_json.h"
#include "protocol/json_schema.h"
#include "protocol/report_json.h"
#include "sim/gcode/interpreter.h"

namespace mdhd::service {
namespace {

using Clock = std::chrono::steady_clock;

// A dry interpretation over its budget (service_job.h): a canned cycle of a hundred
// million pecks is one block, a hundred million lines of loops run for minutes.
struct DryBudgetSpent {};

// Interpretation only: every motion is dropped. Lines read and motions both tick;
// every 1024th tick past the deadline stops the run (the clock is not read per line).
class NullSink : public gcode::MotionSink {
 public:
  explicit NullSink(Clock::time_point deadline) : deadline_(deadline) {}
  void motion(const gcode::Motion&) override { tick(); }
  void tick() {
    if ((++ticks_ & 1023u) == 0 && Clock::now() > deadline_) throw DryBudgetSpent{};
  }

 private:
  Clock::time_point deadline_;
  std::uint64_t ticks_ = 0;
};

HttpError fieldError(const std::string& field, const std::string& message,
                     nlohmann::json extra = nlohmann::json::object()) {
  extra["field"] = field;
  return HttpError(400, "bad_field", field + ": " + message, std::move(extra));
}

void resolveMachine(
    nlohmann::json& doc, AcceptedJob& out,
    const std::function<std::optional<nlohmann::json>(const std::string&)>& lookup) {
  const auto it = doc.find("machine");
  if (it == doc.end() || !it->is_string()) return;
  const std::string name = it->get<std::string>();
  if (!isMachineName(name)) throw fieldError("machine", "not a machine name: \"" + name + "\"");
  std::optional<nlohmann::json> machine = lookup(name);
  if (!machine) {
    throw HttpError(400, "unknown_machine", "machine: no registered machine \"" + name + "\"",
                    {{"field", "machine"}});
  }
  *it = std::move(*machine);
  out.machine_name = name;
}

void dryInterpret(const cli::LoadedJob& loaded, std::chrono::milliseconds budget) {
  NullSink sink(Clock::now() + budget);
  gcode::InterpreterConfig config = cli::interpreterConfig(loaded);
  config.each_line = [&sink] { sink.tick(); };
  gcode::Interpreter interp(std::move(config), sink);
  try {
    interp.run(cli::openProgram(loaded));
  } catch (const DryBudgetSpent&) {
    return;  // no error in what was read in time
  } catch (const gcode::GcodeError& e) {
    nlohmann::json extra = {{"line", e.line()}, {"column", e.column()}};
    if (!e.pos().file.empty()) extra["file"] = e.pos().file;
    const std::string block = cli::programLine(loaded, e.line());
    if (e.pos().file.empty() && !block.empty()) extra["block"] = block;
    throw HttpError(422, "program_error",
                    "program line " + std::to_string(e.line()) + ", column " +
                        std::to_string(e.column()) + ": " + e.what(),
                    std::move(extra));
  }
}

}  // namespace

AcceptedJob acceptJob(
    nlohmann::json doc, std::size_t maxProgramBytes,
    const std::function<std::optional<nlohmann::json>(const std::string&)>& lookupMachine,
    std::chrono::milliseconds interpretBudget) {
  if (!doc.is_object()) throw fieldError("(document)", "a job must be a JSON object");
  for (const char* fileField : {"machine_file", "program_file"}) {
    if (doc.contains(fileField)) {
      throw fieldError(fileField,
                       "files are for the command line; send the content inline (\"machine\" "
                       "or a registered machine's name, \"program\")");
    }
  }
  const auto program = doc.find("program");
  if (program != doc.end() && program->is_string() &&
      program->get_ref<const std::string&>().size() > maxProgramBytes) {
    throw HttpError(
        413, "program_too_large",
        "the program is longer than the limit of " + std::to_string(maxProgramBytes) + " bytes",
        {{"field", "program"}});
  }
  AcceptedJob out;
  resolveMachine(doc, out, lookupMachine);
  const auto problems = protocol::jobSchema().validate(doc);
  if (!problems.empty()) {
    nlohmann::json all = nlohmann::json::array();
    for (const auto& p : problems) all.push_back({{"field", p.path}, {"message", p.message}});
    throw fieldError(problems.front().path, problems.front().message, {{"problems", all}});
  }
  cli::LoadedJob loaded;
  try {
    loaded.job = protocol::jobFromJson(doc);
    cli::requireStockFits(loaded.job);
  } catch (const protocol::FieldError& e) {
    throw fieldError(e.field(), e.message());
  }
  dryInterpret(loaded, interpretBudget);
  out.doc = std::move(doc);
  return out;
}

std::string errorReportText(const std::string& message, const std::string& field) {
  return protocol::reportToJson(cli::errorReport({message, field, "", 0, 0, ""}), nullptr).dump();
}

JobOutcome runServiceJob(const std::string& jobJson, const std::filesystem::path& meshPath,
                         cli::CheckControls controls, std::uint64_t maxMeshBytes) {
  const Clock::time_point started = Clock::now();
  cli::LoadedJob loaded;  // no base_dir: a stored job reaches no file (o-word calls included)
  try {
    loaded.job = protocol::jobFromJson(protocol::parseJsonText(jobJson));
  } catch (const protocol::FieldError& e) {
    return {"failed", errorReportText(e.message(), e.field()), false, "", 0};
  }
  const double loadMs = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
  JobOutcome out;
  controls.finished = [&](const mdh::Stock& stock) {
    const cli::StlOutcome written =
        cli::writeStockStl(stock, meshPath, controls.threads, {controls.cancel, maxMeshBytes});
    out.mesh_error = written.error;
    out.mesh = written.failure == cli::StlOutcome::Failure::kNone;
    if (!out.mesh) {
      out.mesh_error_code = written.failure == cli::StlOutcome::Failure::kTooLarge
                                ? "mesh_too_large"
                                : "mesh_write_failed";
    }
  };
  check::Report report = cli::runCheckJob(loaded, controls);
  report.timing.load_ms = loadMs;
  report.timing.total_ms += loadMs;
  out.moves = report.stats.moves.total();
  out.status = report.status == check::Status::kError ? "failed" : "done";
  out.report = protocol::reportToJson(report, &*loaded.job.machine).dump();
  return out;
}

}  // namespace mdhd::service

#include "daemon/check_runner.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>

#include "protocol/job_json.h"
#include "protocol/json_schema.h"
#include "sim/gcode/interpreter.h"
#include "sim/geometry/static_solids.h"

namespace mdhd::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Lines of the main program, for the progress fraction (one streaming pass).
std::int64_t countLines(const LoadedJob& loaded) {
  std::int64_t n = 0;
  if (loaded.job.program) {
    for (char c : *loaded.job.program) n += c == '\n';
    return n + 1;
  }
  std::ifstream in(loaded.program_path, std::ios::binary);
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) n += buf[i] == '\n';
  }
  return n + 1;
}

}  // namespace

std::vector<std::unique_ptr<geom::LineSolid>> fixtureSolids(const protocol::Job& job) {
  std::vector<std::unique_ptr<geom::LineSolid>> out;
  for (const protocol::Fixture& f : job.fixtures) {
    if (f.kind == protocol::Fixture::Kind::kBox) {
      out.push_back(std::make_unique<geom::BoxSolid>(f.box.lo, f.box.hi));
    } else {
      out.push_back(std::make_unique<geom::CylinderSolid>(f.base, f.axis, f.radius, f.height));
    }
  }
  return out;
}

check::SimulationOptions simulationOptions(const protocol::JobOptions& o) {
  check::SimulationOptions s;
  s.density = o.density;
  s.steps = o.steps;
  s.tolerance = o.tolerance;
  s.ruleset.clear();
  for (const std::string& name : o.ruleset) {
    if (const auto rule = mdh::ruleFromName(name)) s.ruleset.push_back(*rule);
  }
  s.seed = o.seed;
  s.three_way = o.three_way;
  s.two_sided = o.two_sided;
  s.contact_tolerance = o.contactTolerance();
  s.chain_tolerance = o.chainTolerance();
  return s;
}

void requireStockFits(const protocol::Job& job) {
  const std::string problem = check::Simulation::stockProblem(*job.machine, job.tools, job.stock,
                                                              simulationOptions(job.options));
  if (!problem.empty()) throw protocol::FieldError("options.density", problem);
}

LoadedJob loadCheckedJobFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw protocol::FieldError("(file)", "cannot open " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  const nlohmann::json doc = protocol::parseJsonText(text.str());
  const auto problems = protocol::jobSchema().validate(doc);
  if (!problems.empty()) {
    throw protocol::FieldError(problems.front().path, problems.front().message);
  }
  return loadJobFile(path);
}

std::string programLine(const LoadedJob& loaded, int line) {
  if (line <= 0) return {};
  std::unique_ptr<std::istream> in;
  if (loaded.job.program) {
    in = std::make_unique<std::istringstream>(*loaded.job.program);
  } else {
    in = std::make_unique<std::ifstream>(loaded.program_path, std::ios::binary);
  }
  std::string text;
  for (int i = 0; i < line; ++i) {
    if (!std::getline(*in, text)) return {};
  }
  if (!text.empty() && text.back() == '\r') text.pop_back();
  return text;
}

check::Report errorReport(check::ReportError error) {
  check::Report r;
  r.status = check::Status::kError;
  r.error = std::move(error);
  return r;
}

check::Report runCheckJob(const LoadedJob& loaded, const CheckControls& controls) {
  const Clock::time_point started = Clock::now();
  const protocol::Job& job = loaded.job;
  std::unique_ptr<kin::Kinematics> kin;
  std::unique_ptr<check::Simulation> sim;
  try {
    requireStockFits(job);
  } catch (const protocol::FieldError& e) {
    return errorReport({e.message(), e.field(), "", 0, 0, ""});
  }
  try {
    kin = std::make_unique<kin::Kinematics>(*job.machine);
    check::SimulationOptions options = simulationOptions(job.options);
    options.threads = std::max(1, controls.threads);
    if (controls.batch_steps > 0) options.batch_steps = controls.batch_steps;
    sim = std::make_unique<check::Simulation>(*kin, job.tools, job.stock, fixtureSolids(job),
                                              options);
  } catch (const std::exception& e) {
    return errorReport({e.what(), "(job)", "", 0, 0, ""});
  }
  if (controls.cancel != nullptr) sim->setCancelFlag(controls.cancel);
  if (controls.progress) {
    const double lines = static_cast<double>(countLines(loaded));
    // `lines` by value: it lives in this block, the callback as long as the run.
    sim->setProgress([&controls, lines](const gcode::SourcePos& pos, std::int64_t moves) {
      if (pos.file.empty()) controls.progress(std::min(1.0, pos.line / lines), moves);
    });
  }
  gcode::InterpreterConfig config = interpreterConfig(loaded);
  if (controls.cancel != nullptr) {
    // The simulation looks at the flag every step; lines without motion (an o-word
    // loop of assignments) look here.
    const std::atomic<bool>* cancel = controls.cancel;
    config.each_line = [cancel] {
      if (cancel->load(std::memory_order_relaxed)) throw check::Cancelled();
    };
  }
  gcode::Interpreter interp(std::move(config), *sim);
  try {
    interp.run(openProgram(loaded));
  } catch (const gcode::GcodeError& e) {
    check::ReportError error{e.what(), "", e.pos().file, e.line(), e.column(), ""};
    if (e.pos().file.empty()) error.block = programLine(loaded, e.line());
    return errorReport(std::move(error));
  } catch (const protocol::FieldError& e) {
    return errorReport({e.message(), e.field(), "", 0, 0, ""});
  } catch (const check::Cancelled&) {
    throw;
  } catch (const std::exception& e) {
    // A failure of the engine itself: still a report, never a crash.
    return errorReport({std::string("internal error: ") + e.what(), "(engine)", "", 0, 0, ""});
  }
  check::Report report = sim->finish(static_cast<std::int64_t>(interp.blocksExecuted()));
  if (controls.finished) controls.finished(sim->stock());
  report.timing.total_ms =
      std::chrono::duration<double, std::milli>(Clock::now() - started).count();
  return report;
}

}  // namespace mdhd::cli

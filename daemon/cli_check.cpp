// mdhd check JOB.json [--report R.json] [--mesh M.stl] [--threads N] [--batch N]: the whole
// pre-run check.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <ostream>
#include <thread>

#include "daemon/check_runner.h"
#include "daemon/cli.h"
#include "daemon/stock_stl.h"
#include "protocol/json_fields.h"
#include "protocol/report_json.h"

namespace mdhd::cli {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kCheckUsage =
    "usage: mdhd check JOB.json [--report REPORT.json] [--mesh RESULT.stl] [--threads N] "
    "[--batch N]\n";

struct CheckArgs {
  std::string job;
  std::string report;
  std::string mesh;
  int threads = 0;  // 0: one per core
  int batch = 0;    // feed steps cut at once; 0: the default
};

// A count from 0 to 256 (the cutting threads, 0: the machine's cores; the batch size).
bool parseCount(const std::string& text, int& out) {
  if (text.empty() || text.size() > 3 || text.find_first_not_of("0123456789") != std::string::npos)
    return false;
  out = std::stoi(text);
  return out <= 256;
}

bool parseArgs(const Args& args, CheckArgs& out, std::ostream& err) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--report" || a == "--mesh") {
      if (i + 1 >= args.size() || args[i + 1].empty()) {
        err << "mdhd check: " << a << " needs a file name\n" << kCheckUsage;
        return false;
      }
      (a == "--report" ? out.report : out.mesh) = args[++i];
    } else if (a == "--threads") {
      if (i + 1 >= args.size() || !parseCount(args[i + 1], out.threads)) {
        err << "mdhd check: --threads needs a count from 0 (one per core) to 256\n" << kCheckUsage;
        return false;
      }
      ++i;
    } else if (a == "--batch") {
      if (i + 1 >= args.size() || !parseCount(args[i + 1], out.batch) || out.batch < 1) {
        err << "mdhd check: --batch needs a count of steps from 1 (one by one) to 256\n"
            << kCheckUsage;
        return false;
      }
      ++i;
    } else if (!a.empty() && a[0] == '-') {
      err << "mdhd check: unknown option '" << a << "'\n" << kCheckUsage;
      return false;
    } else if (out.job.empty()) {
      out.job = a;
    } else {
      err << "mdhd check: one job at a time ('" << a << "' is extra)\n" << kCheckUsage;
      return false;
    }
  }
  if (out.job.empty()) {
    err << kCheckUsage;
    return false;
  }
  return true;
}

// Progress on stderr: a bar redrawn at most 10 times a second on a terminal,
// otherwise a plain line every 2 seconds once the run has taken 2 seconds.
class ProgressPrinter {
 public:
  ProgressPrinter(std::ostream& err, bool tty) : err_(err), tty_(tty), start_(Clock::now()) {}
  void update(double fraction, std::int64_t moves) {
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (tty_) {
      if (since < 0.1) return;
      constexpr int kWidth = 30;
      const int filled = static_cast<int>(fraction * kWidth);
      char line[160];
      std::snprintf(line, sizeof line, "\r[%-*s] %3d%%  %lld moves  %.1f s", kWidth,
                    std::string(static_cast<std::size_t>(filled), '#').c_str(),
                    static_cast<int>(fraction * 100), static_cast<long long>(moves), elapsed);
      err_ << line << std::flush;
      drawn_ = true;
    } else {
      if (elapsed < 2.0 || since < 2.0) return;
      char line[160];
      std::snprintf(line, sizeof line, "mdhd check: %d%% of the program, %lld moves, %.1f s\n",
                    static_cast<int>(fraction * 100), static_cast<long long>(moves), elapsed);
      err_ << line << std::flush;
    }
    last_ = now;
  }
  void done() {
    if (drawn_) err_ << "\r" << std::string(60, ' ') << "\r" << std::flush;
  }

 private:
  std::ostream& err_;
  bool tty_;
  Clock::time_point start_;
  Clock::time_point last_{};
  bool drawn_ = false;
};

std::string describeError(const check::ReportError& e, const std::string& job) {
  if (e.line == 0 && e.file.empty()) {
    return job + ": " + (e.field.empty() ? "" : e.field + ": ") + e.message;
  }
  return (e.file.empty() ? std::string("program") : e.file) + ", line " + std::to_string(e.line) +
         ", column " + std::to_string(e.column) + ": " + e.message +
         (e.block.empty() ? "" : "\n  " + e.block);
}

int exitStatus(check::Status s) {
  switch (s) {
    case check::Status::kClean:
      return 0;
    case check::Status::kCollisions:
      return 1;
    case check::Status::kError:
      return 2;
  }
  return 2;
}

// Writes the report where asked; false (with a message) when it cannot.
bool writeReport(const nlohmann::json& doc, const std::string& path, std::ostream& out,
                 std::ostream& err) {
  const std::string text = doc.dump(2) + "\n";
  if (path.empty()) {
    out << text << std::flush;
    return true;
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (file) file << text;
  if (!file || !file.flush()) {
    err << "mdhd check: cannot write the report to " << path << "\n";
    return false;
  }
  return true;
}

}  // namespace

int runCheck(const Args& args, std::ostream& out, std::ostream& err) {
  CheckArgs a;
  if (!parseArgs(args, a, err)) return 2;
  const Clock::time_point started = Clock::now();
  LoadedJob loaded;
  check::Report report;
  bool haveMachine = false;
  bool meshFailed = false;
  try {
    loaded = loadCheckedJobFile(a.job);
    haveMachine = true;
  } catch (const protocol::FieldError& e) {
    report = errorReport({e.message(), e.field(), "", 0, 0, ""});
  }
  if (haveMachine) {
    const double loadMs = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
    const bool tty = &err == &std::cerr && isatty(STDERR_FILENO) == 1;
    ProgressPrinter progress(err, tty);
    CheckControls controls;
    controls.threads = a.threads > 0
                           ? a.threads
                           : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    controls.batch_steps = a.batch;
    controls.progress = [&](double fraction, std::int64_t moves) {
      progress.update(fraction, moves);
    };
    std::string meshError;
    if (!a.mesh.empty()) {
      controls.finished = [&](const mdh::Stock& stock) {
        meshError = writeStockStl(stock, a.mesh, controls.threads);
      };
    }
    report = runCheckJob(loaded, controls);
    progress.done();
    if (!meshError.empty()) {
      err << "mdhd check: --mesh: " << meshError << "\n";
      meshFailed = true;
    }
    report.timing.load_ms = loadMs;
    report.timing.total_ms += loadMs;
  }
  if (report.error) err << "mdhd check: " << describeError(*report.error, a.job) << "\n";
  const nlohmann::json doc =
      protocol::reportToJson(report, haveMachine ? &*loaded.job.machine : nullptr);
  if (!writeReport(doc, a.report, out, err) || meshFailed) return 2;
  return exitStatus(report.status);
}

}  // namespace mdhd::cli

// mdhd serve [--config FILE] [flags]: the HTTP service until SIGTERM or SIGINT.
#include <signal.h>

#include <iostream>
#include <ostream>

#include "daemon/cli.h"
#include "daemon/service.h"

namespace mdhd::cli {
namespace {

constexpr const char* kServeUsage =
    "usage: mdhd serve [--config FILE] [--bind ADDR] [--port P] [--data-dir DIR]\n"
    "                  [--token T]... [--workers N] [--http-threads N] [--queue-limit N]\n"
    "                  [--max-body-bytes N] [--max-program-bytes N] [--max-job-seconds S]\n"
    "                  [--max-mesh-mb N]\n"
    "                  [--shutdown-grace-seconds S] [--max-interruptions N] [--log-file FILE]\n"
    "                  [--no-example-machines] [--check-config]\n"
    "Settings: embedded defaults < config file < MDHD_* environment < flags (docs/daemon.md).\n"
    "--check-config: read the settings, say whether the service could start with them\n"
    "(exit 0 or 2), and start nothing.\n";

// The settings that matter to an administrator, tokens counted and never shown.
void printSettings(const service::ServiceConfig& c, std::ostream& out) {
  out << "bind " << c.bind << ":" << c.port << ", data dir " << c.data_dir << ", "
      << c.tokens.size() << (c.tokens.size() == 1 ? " token" : " tokens") << ", "
      << service::effectiveWorkers(c) << " workers, queue limit " << c.queue_limit << ", log "
      << (c.log_file.empty() ? "stderr" : c.log_file) << "\n";
}

}  // namespace

int runServe(const Args& args, std::ostream& out, std::ostream& err) {
  for (const std::string& a : args) {
    if (a == "--help" || a == "-h") {
      out << kServeUsage;
      return 0;
    }
  }
  Args flags;
  bool checkOnly = false;
  for (const std::string& a : args) {
    if (a == "--check-config") {
      checkOnly = true;
    } else {
      flags.push_back(a);
    }
  }
  service::ServiceConfig config;
  try {
    const auto env = service::processEnvironment();
    const std::string path = service::configPath(flags, env);
    if (!path.empty()) service::applyConfigFile(config, path);
    service::applyEnvironment(config, env);
    service::applyFlags(config, flags);
  } catch (const protocol::FieldError& e) {
    err << "mdhd serve: " << e.what() << "\n" << kServeUsage;
    return 2;
  }
  if (checkOnly) {
    const std::string problem = service::configProblem(config);
    if (!problem.empty()) {
      err << "mdhd serve: " << problem << "\n";
      return 2;
    }
    out << "mdhd serve: configuration OK: ";
    printSettings(config, out);
    return 0;
  }
  // Signals are taken by sigwait below, so block them before any thread starts.
  sigset_t stopSignals;
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGTERM);
  sigaddset(&stopSignals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);
  signal(SIGPIPE, SIG_IGN);
  try {
    service::Service svc(config);
    svc.start();
    out << "mdhd serve: listening on " << config.bind << ":" << svc.port() << std::endl;
    int sig = 0;
    sigwait(&stopSignals, &sig);
    svc.log().write("signal", {{"signal", sig == SIGTERM ? "SIGTERM" : "SIGINT"}});
    svc.stop();
  } catch (const std::exception& e) {
    err << "mdhd serve: " << e.what() << "\n";
    return 2;
  }
  return 0;
}

}  // namespace mdhd::cli

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
    "                  [--no-example-machines]\n"
    "Settings: embedded defaults < config file < MDHD_* environment < flags (docs/daemon.md).\n";

}  // namespace

int runServe(const Args& args, std::ostream& out, std::ostream& err) {
  for (const std::string& a : args) {
    if (a == "--help" || a == "-h") {
      out << kServeUsage;
      return 0;
    }
  }
  service::ServiceConfig config;
  try {
    const auto env = service::processEnvironment();
    const std::string path = service::configPath(args, env);
    if (!path.empty()) service::applyConfigFile(config, path);
    service::applyEnvironment(config, env);
    service::applyFlags(config, args);
  } catch (const protocol::FieldError& e) {
    err << "mdhd serve: " << e.what() << "\n" << kServeUsage;
    return 2;
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

#pragma once
// Settings of `mdhd serve`: embedded defaults that work on a fresh machine, then a
// JSON config file, then MDHD_* environment variables, then command-line flags,
// each later source overriding the earlier ones (docs/daemon.md lists them all).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "protocol/json_fields.h"

namespace mdhd::service {

struct ServiceConfig {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port (printed on start)
  std::string data_dir = "var/mdhd";
  std::vector<std::string> tokens;  // bearer tokens; required unless bound to loopback
  int workers = 0;                  // simulation workers; 0: one per core
  int http_threads = 16;            // connection threads (each keep-alive client holds one)
  std::size_t queue_limit = 64;     // jobs waiting to run; more are refused with 429
  std::size_t max_body_bytes = 16u << 20;
  std::size_t max_program_bytes = 8u << 20;
  double max_job_seconds = 3600.0;       // a job running longer fails
  std::uint64_t max_mesh_mb = 512;       // a larger final stock STL is not written
  double shutdown_grace_seconds = 10.0;  // on SIGTERM: running jobs may finish this long
  int max_interruptions = 3;     // a job the process died under this often fails, not reruns
  std::string log_file;          // empty: stderr
  bool example_machines = true;  // register the preset machines on first start
};

// Reads a config file (a JSON object with the field names above; unknown fields
// are errors). Throws protocol::FieldError naming the field.
void applyConfigFile(ServiceConfig& config, const std::string& path);

// Applies MDHD_BIND, MDHD_PORT, ... (docs/daemon.md). `env` maps names to values.
void applyEnvironment(ServiceConfig& config, const std::map<std::string, std::string>& env);

// The process's MDHD_* environment variables.
std::map<std::string, std::string> processEnvironment();

// Applies flags (--bind, --port, --token, ...); `--config` is read by the caller
// first. Throws protocol::FieldError naming the flag.
void applyFlags(ServiceConfig& config, const std::vector<std::string>& flags);

// The --config value among the flags, else MDHD_CONFIG, else "".
std::string configPath(const std::vector<std::string>& flags,
                       const std::map<std::string, std::string>& env);

// Whether `host` is a loopback address (127.0.0.0/8, ::1, localhost).
bool isLoopback(const std::string& host);

// What makes the configuration unusable ("" when fine): bad ranges, and no token
// while binding beyond loopback.
std::string configProblem(const ServiceConfig& config);

// Worker count after applying the 0 = one per core default.
int effectiveWorkers(const ServiceConfig& config);

}  // namespace mdhd::service

#include "daemon/service_config.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "daemon/number_text.h"
#include "protocol/job_json.h"

extern char** environ;

namespace mdhd::service {
namespace {

using nlohmann::json;
using protocol::FieldError;

// One setting: its name in the file, the env variable and the flag, and how a
// text value (env, flag) or a JSON value (file) is stored.
struct Setting {
  const char* name;
  const char* env;
  const char* flag;
  void (*fromText)(ServiceConfig&, const std::string& text, const std::string& where);
  void (*fromJson)(ServiceConfig&, const json& value, const std::string& where);
};

long long parseInteger(const std::string& text, const std::string& where, long long lo,
                       long long hi) {
  const std::optional<long long> v = integerInRange(text, lo, hi);
  if (!v) {
    throw FieldError(where, "expected an integer from " + std::to_string(lo) + " to " +
                                std::to_string(hi) + ", got \"" + text + "\"");
  }
  return *v;
}

double parseSeconds(const std::string& text, const std::string& where) {
  const std::optional<double> v = numberInRange(text, 0.0, 1e9);
  if (!v || !(*v > 0.0)) {
    throw FieldError(where, "expected a positive number of seconds, got \"" + text + "\"");
  }
  return *v;
}

long long jsonInteger(const json& j, const std::string& where, long long lo, long long hi) {
  if (!j.is_number_integer() || j.get<long long>() < lo || j.get<long long>() > hi) {
    protocol::fields::fail(
        where, "an integer from " + std::to_string(lo) + " to " + std::to_string(hi), j);
  }
  return j.get<long long>();
}

double jsonSeconds(const json& j, const std::string& where) {
  const double v = protocol::fields::positive(j, where);
  if (v > 1e9) protocol::fields::fail(where, "at most 1e9 seconds", j);
  return v;
}

std::vector<std::string> splitTokens(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string t;
  while (std::getline(in, t, ',')) {
    if (!t.empty()) out.push_back(t);
  }
  return out;
}

constexpr long long kMaxBytes = 1ll << 34;

const Setting kSettings[] = {
    {"bind", "MDHD_BIND", "--bind",
     [](ServiceConfig& c, const std::string& t, const std::string&) { c.bind = t; },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.bind = protocol::fields::string(j, w);
     }},
    {"port", "MDHD_PORT", "--port",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.port = static_cast<int>(parseInteger(t, w, 0, 65535));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.port = static_cast<int>(jsonInteger(j, w, 0, 65535));
     }},
    {"data_dir", "MDHD_DATA_DIR", "--data-dir",
     [](ServiceConfig& c, const std::string& t, const std::string&) { c.data_dir = t; },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.data_dir = protocol::fields::string(j, w);
     }},
    {"tokens", "MDHD_TOKENS", "--token",
     [](ServiceConfig& c, const std::string& t, const std::string&) {
       for (auto& token : splitTokens(t)) c.tokens.push_back(token);
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       if (!j.is_array()) protocol::fields::fail(w, "an array of strings", j);
       c.tokens.clear();
       for (std::size_t i = 0; i < j.size(); ++i) {
         c.tokens.push_back(protocol::fields::string(j[i], w + "[" + std::to_string(i) + "]"));
       }
     }},
    {"workers", "MDHD_WORKERS", "--workers",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.workers = static_cast<int>(parseInteger(t, w, 0, 256));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.workers = static_cast<int>(jsonInteger(j, w, 0, 256));
     }},
    {"http_threads", "MDHD_HTTP_THREADS", "--http-threads",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.http_threads = static_cast<int>(parseInteger(t, w, 2, 1024));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.http_threads = static_cast<int>(jsonInteger(j, w, 2, 1024));
     }},
    {"queue_limit", "MDHD_QUEUE_LIMIT", "--queue-limit",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.queue_limit = static_cast<std::size_t>(parseInteger(t, w, 1, 1000000));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.queue_limit = static_cast<std::size_t>(jsonInteger(j, w, 1, 1000000));
     }},
    {"max_body_bytes", "MDHD_MAX_BODY_BYTES", "--max-body-bytes",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.max_body_bytes = static_cast<std::size_t>(parseInteger(t, w, 1024, kMaxBytes));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.max_body_bytes = static_cast<std::size_t>(jsonInteger(j, w, 1024, kMaxBytes));
     }},
    {"max_program_bytes", "MDHD_MAX_PROGRAM_BYTES", "--max-program-bytes",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.max_program_bytes = static_cast<std::size_t>(parseInteger(t, w, 1, kMaxBytes));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.max_program_bytes = static_cast<std::size_t>(jsonInteger(j, w, 1, kMaxBytes));
     }},
    {"max_job_seconds", "MDHD_MAX_JOB_SECONDS", "--max-job-seconds",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.max_job_seconds = parseSeconds(t, w);
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.max_job_seconds = jsonSeconds(j, w);
     }},
    {"max_mesh_mb", "MDHD_MAX_MESH_MB", "--max-mesh-mb",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.max_mesh_mb = static_cast<std::uint64_t>(parseInteger(t, w, 1, 1 << 20));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.max_mesh_mb = static_cast<std::uint64_t>(jsonInteger(j, w, 1, 1 << 20));
     }},
    {"shutdown_grace_seconds", "MDHD_SHUTDOWN_GRACE_SECONDS", "--shutdown-grace-seconds",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.shutdown_grace_seconds = t == "0" ? 0.0 : parseSeconds(t, w);
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.shutdown_grace_seconds = j.is_number() && j.get<double>() == 0.0 ? 0.0 : jsonSeconds(j, w);
     }},
    {"max_interruptions", "MDHD_MAX_INTERRUPTIONS", "--max-interruptions",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       c.max_interruptions = static_cast<int>(parseInteger(t, w, 1, 1000));
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.max_interruptions = static_cast<int>(jsonInteger(j, w, 1, 1000));
     }},
    {"log_file", "MDHD_LOG_FILE", "--log-file",
     [](ServiceConfig& c, const std::string& t, const std::string&) { c.log_file = t; },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.log_file = protocol::fields::string(j, w);
     }},
    {"example_machines", "MDHD_EXAMPLE_MACHINES", "--example-machines",
     [](ServiceConfig& c, const std::string& t, const std::string& w) {
       if (t != "true" && t != "false") {
         throw FieldError(w, "expected true or false, got \"" + t + "\"");
       }
       c.example_machines = t == "true";
     },
     [](ServiceConfig& c, const json& j, const std::string& w) {
       c.example_machines = protocol::fields::boolean(j, w);
     }},
};

}  // namespace

void applyConfigFile(ServiceConfig& config, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FieldError("--config", "cannot open " + path);
  std::ostringstream text;
  text << in.rdbuf();
  const json doc = protocol::parseJsonText(text.str());
  if (!doc.is_object()) protocol::fields::fail(path, "a JSON object", doc);
  for (const auto& [key, value] : doc.items()) {
    const Setting* setting = nullptr;
    for (const Setting& s : kSettings) {
      if (key == s.name) setting = &s;
    }
    if (setting == nullptr) throw FieldError(path + ": " + key, "unknown setting");
    setting->fromJson(config, value, path + ": " + key);
  }
}

void applyEnvironment(ServiceConfig& config, const std::map<std::string, std::string>& env) {
  for (const Setting& s : kSettings) {
    const auto it = env.find(s.env);
    if (it != env.end()) {
      if (std::string(s.name) == "tokens") config.tokens.clear();
      s.fromText(config, it->second, s.env);
    }
  }
}

std::map<std::string, std::string> processEnvironment() {
  std::map<std::string, std::string> env;
  for (char** e = environ; e != nullptr && *e != nullptr; ++e) {
    const std::string entry(*e);
    const auto eq = entry.find('=');
    if (eq != std::string::npos && entry.rfind("MDHD_", 0) == 0) {
      env[entry.substr(0, eq)] = entry.substr(eq + 1);
    }
  }
  return env;
}

void applyFlags(ServiceConfig& config, const std::vector<std::string>& flags) {
  bool tokensGiven = false;
  for (std::size_t i = 0; i < flags.size(); ++i) {
    const std::string& flag = flags[i];
    if (flag == "--no-example-machines") {
      config.example_machines = false;
      continue;
    }
    if (flag == "--config") {
      ++i;  // read by the caller
      continue;
    }
    const Setting* setting = nullptr;
    for (const Setting& s : kSettings) {
      if (flag == s.flag) setting = &s;
    }
    if (setting == nullptr) throw FieldError(flag, "unknown option");
    if (i + 1 >= flags.size()) throw FieldError(flag, "needs a value");
    if (std::string(setting->name) == "tokens" && !tokensGiven) {
      config.tokens.clear();  // flags replace tokens from the file or the environment
      tokensGiven = true;
    }
    setting->fromText(config, flags[++i], flag);
  }
}

std::string configPath(const std::vector<std::string>& flags,
                       const std::map<std::string, std::string>& env) {
  for (std::size_t i = 0; i + 1 < flags.size(); ++i) {
    if (flags[i] == "--config") return flags[i + 1];
  }
  const auto it = env.find("MDHD_CONFIG");
  return it == env.end() ? "" : it->second;
}

bool isLoopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

std::string configProblem(const ServiceConfig& config) {
  if (config.bind.empty()) return "bind: empty address";
  if (config.data_dir.empty()) return "data_dir: empty path";
  for (const std::string& t : config.tokens) {
    if (t.size() < 16) return "tokens: a token shorter than 16 characters is too easy to guess";
  }
  if (!isLoopback(config.bind) && config.tokens.empty()) {
    return "binding " + config.bind +
           " (beyond loopback) needs at least one bearer token (tokens in the config file, "
           "MDHD_TOKENS or --token)";
  }
  return "";
}

int effectiveWorkers(const ServiceConfig& config) {
  if (config.workers > 0) return config.workers;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace mdhd::service

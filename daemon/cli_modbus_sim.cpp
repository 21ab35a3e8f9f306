// mdhd modbus-sim JOB.json --port P [--speed S] [--host H] [--map MAP.json] [--loop]
//                [--exit-after SEC]
// A simulated controller: plays the job's program in real time and serves the
// machine's joints, tool, spindle and line over Modbus TCP (docs/modbus.md).
#include <csignal>
#include <fstream>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>

#include "daemon/cli.h"
#include "daemon/job_files.h"
#include "daemon/modbus_server.h"
#include "daemon/virtual_machine.h"
#include "protocol/job_json.h"
#include "protocol/machine_json.h"
#include "protocol/modbus_map_json.h"
#include "sim/gcode/interpreter.h"
#include "sim/kinematics/motion_time.h"

namespace mdhd::cli {
namespace {

using protocol::FieldError;

constexpr const char* kModbusSimUsage =
    "usage: mdhd modbus-sim JOB.json --port P [--speed S] [--host H] [--map MAP.json] [--loop] "
    "[--exit-after SEC]\n";

volatile std::sig_atomic_t g_stop = 0;
extern "C" void onStopSignal(int) {
  g_stop = 1;
}

struct SimArgs {
  std::string job;
  std::string host = "127.0.0.1";
  int port = -1;
  double speed = 1.0;
  std::string map;
  bool loop = false;
  std::optional<double> exit_after;
};

double parseNumber(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v)) {
    throw std::invalid_argument(flag + " expects a number, got '" + text + "'");
  }
  return v;
}

SimArgs parseArgs(const Args& args) {
  SimArgs a;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(arg + " needs a value");
      return args[++i];
    };
    if (arg == "--port") {
      const double p = parseNumber(arg, value());
      if (p != std::floor(p) || p < 0 || p > 65535) {
        throw std::invalid_argument("--port expects 0..65535 (0: any free port)");
      }
      a.port = static_cast<int>(p);
    } else if (arg == "--speed") {
      a.speed = parseNumber(arg, value());
      if (!(a.speed > 0.0 && a.speed <= 1e6)) throw std::invalid_argument("--speed expects > 0");
    } else if (arg == "--host") {
      a.host = value();
    } else if (arg == "--map") {
      a.map = value();
    } else if (arg == "--loop") {
      a.loop = true;
    } else if (arg == "--exit-after") {
      a.exit_after = parseNumber(arg, value());
      if (!(*a.exit_after >= 0.0)) throw std::invalid_argument("--exit-after expects >= 0");
    } else if (!arg.empty() && arg[0] != '-' && a.job.empty()) {
      a.job = arg;
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (a.job.empty()) throw std::invalid_argument("no job file given");
  if (a.port < 0) throw std::invalid_argument("--port is required");
  return a;
}

std::string readText(const std::string& path, const std::string& field) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FieldError(field, "cannot open " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The job, and its own `modbus` block if it has one. The job codec does not know
// that block yet, so it is taken out before the job is read; such a job is then
// loaded here the way loadJobFile does (machine_file, program_file beside it).
protocol::ModbusMap chooseMap(const SimArgs& a, const std::optional<nlohmann::json>& job_block,
                              const kin::Machine& machine) {
  if (!a.map.empty()) {
    nlohmann::json doc = protocol::parseJsonText(readText(a.map, "--map"));
    // Either the block itself or a document holding it (a shadow request, a job).
    if (doc.is_object() && doc.contains("modbus"))
      return protocol::modbusMapFromJson(doc["modbus"], "modbus", &machine);
    return protocol::modbusMapFromJson(doc, "modbus", &machine);
  }
  if (job_block) return protocol::modbusMapFromJson(*job_block, "modbus", &machine);
  return protocol::defaultModbusMap(machine);
}

void installSignals() {
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  signal(SIGPIPE, SIG_IGN);  // a vanished client is an error on its socket, not a kill
}

int simulate(const SimArgs& a, std::ostream& out, std::ostream& err) {
  const LoadedJob loaded = loadJobFile(a.job);
  const kin::Kinematics kin(*loaded.job.machine);
  const protocol::ModbusMap map = chooseMap(a, loaded.job.modbus, *loaded.job.machine);

  daemon::ModbusServerOptions options;
  options.host = a.host;
  options.port = a.port;
  options.table = map.table;
  options.registers = protocol::registerSpan(map);
  options.coils = map.feed_hold.coil + 1;
  // The machine at home, tool 0, spindle off, line 0 from the first reply on.
  std::vector<std::uint16_t> image(static_cast<std::size_t>(options.registers));
  protocol::ModbusSample home;
  home.joints = loaded.job.machine->home;
  home.tool = 0;
  home.spindle_on = false;
  home.line = 0;
  protocol::encodeSample(map, home, image);
  options.initial = image;
  daemon::ModbusServer server(options);
  out << "listening on " << a.host << ":" << server.port() << std::endl;

  const auto started = std::chrono::steady_clock::now();
  daemon::PlaybackHooks hooks;
  hooks.publish = [&](const daemon::ControllerState& s) {
    protocol::ModbusSample sample;
    sample.joints = s.joints;
    sample.tool = s.tool;
    sample.spindle_on = s.spindle_on;
    sample.line = s.line;
    protocol::encodeSample(map, sample, image);
    server.setRegisters(image);
  };
  hooks.feed_hold = [&] { return server.coil(map.feed_hold.coil); };
  hooks.stop_requested = [&] {
    if (g_stop != 0) return true;
    return a.exit_after &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >=
               *a.exit_after;
  };
  daemon::VirtualMachine vm(kin, loaded.job, hooks, a.speed, err);
  try {
    for (;;) {
      vm.reset(loaded.job.machine->home);
      const double before = vm.programSeconds();
      gcode::Interpreter interp(interpreterConfig(loaded), vm);
      interp.run(openProgram(loaded));
      err << "modbus-sim: program finished (" << std::fixed << std::setprecision(3)
          << vm.programSeconds() - before << " s of machine time)" << std::endl;
      // A program that takes no time would spin: loop only programs that move.
      if (!a.loop || vm.programSeconds() == before) break;
    }
    vm.holdUntilStopped();
  } catch (const daemon::PlaybackStopped&) {
  }
  server.stop();
  return 0;
}

}  // namespace

int runModbusSim(const Args& args, std::ostream& out, std::ostream& err) {
  SimArgs a;
  try {
    a = parseArgs(args);
  } catch (const std::invalid_argument& e) {
    err << "mdhd modbus-sim: " << e.what() << "\n" << kModbusSimUsage;
    return 2;
  }
  g_stop = 0;
  installSignals();
  try {
    return simulate(a, out, err);
  } catch (const gcode::GcodeError& e) {
    const std::string where = e.pos().file.empty() ? "program" : e.pos().file;
    err << "mdhd modbus-sim: " << where << ", line " << e.line() << ", column " << e.column()
        << ": " << e.what() << "\n";
  } catch (const FieldError& e) {
    err << "mdhd modbus-sim: " << e.what() << "\n";
  } catch (const kin::KinematicsError& e) {
    err << "mdhd modbus-sim: machine: " << e.what() << "\n";
  } catch (const kin::MotionTimeError& e) {
    err << "mdhd modbus-sim: program: " << e.what() << "\n";
  } catch (const daemon::ModbusServerError& e) {
    err << "mdhd modbus-sim: " << e.what() << "\n";
  } catch (const protocol::RegisterValueError& e) {
    err << "mdhd modbus-sim: register map: " << e.what() << "\n";
  }
  return 2;
}

}  // namespace mdhd::cli

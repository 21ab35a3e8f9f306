#include "daemon/job_files.h"

#include <exception>
#include <fstream>
#include <memory>
#include <sstream>

#include "protocol/job_json.h"
#include "protocol/machine_json.h"
#include "sim/kinematics/inverse.h"
#include "sim/kinematics/kinematics.h"

namespace mdhd::cli {
namespace {

using protocol::FieldError;

std::string readFile(const std::filesystem::path& path, const std::string& field) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FieldError(field, "cannot open " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::filesystem::path resolve(const std::filesystem::path& base, const std::string& name) {
  const std::filesystem::path p(name);
  return p.is_absolute() ? p : base / p;
}

}  // namespace

LoadedJob loadJobFile(const std::filesystem::path& path) {
  LoadedJob loaded;
  loaded.base_dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  loaded.job = protocol::jobFromJson(protocol::parseJsonText(readFile(path, "(file)")));
  protocol::Job& job = loaded.job;
  if (!job.machine_name.empty()) {
    throw FieldError("machine",
                     "a machine by name needs the service's registry; on the command "
                     "line give the machine object or machine_file");
  }
  if (!job.machine_file.empty()) {
    const auto machine_path = resolve(loaded.base_dir, job.machine_file);
    const std::string text = readFile(machine_path, "machine_file");
    try {
      job.machine = protocol::machineFromJson(protocol::parseJsonText(text), "machine_file");
    } catch (const protocol::FieldError& e) {
      throw FieldError("machine_file", machine_path.string() + ": " + e.what());
    }
  }
  if (!job.program_file.empty()) {
    loaded.program_path = resolve(loaded.base_dir, job.program_file);
    if (!std::filesystem::is_regular_file(loaded.program_path)) {
      throw FieldError("program_file", "cannot open " + loaded.program_path.string());
    }
  }
  return loaded;
}

std::unique_ptr<gcode::LineSource> openProgram(const LoadedJob& loaded) {
  if (loaded.job.program) return gcode::makeStringSource(*loaded.job.program);
  auto in = std::make_unique<std::ifstream>(loaded.program_path, std::ios::binary);
  if (!*in) throw FieldError("program_file", "cannot open " + loaded.program_path.string());
  return gcode::makeStreamSource(std::move(in));
}

gcode::InterpreterConfig interpreterConfig(const LoadedJob& loaded) {
  const protocol::Job& job = loaded.job;
  gcode::InterpreterConfig config;
  config.work_offsets = job.work_offsets;
  config.home = job.machine->home;
  config.axis_mask = 0;
  for (const kin::Joint& joint : job.machine->joints) {
    if (const auto axis = kin::axisOfName(joint.name)) config.axis_mask |= 1u << *axis;
  }
  for (const geom::Tool& tool : job.tools) {
    config.tools.add({tool.number, tool.length, tool.diameter});
  }
  try {
    auto kin = std::make_shared<const kin::Kinematics>(*job.machine);
    config.tcp_switch = [kin](const gcode::AxisValues& m, double length, bool to_tcp) {
      return kin::switchTcp(*kin, m, length, to_tcp);
    };
  } catch (const std::exception&) {
    // A machine the kinematics refuse fails where the run builds its own, with the reason.
  }
  const std::filesystem::path dir =
      loaded.program_path.empty() ? loaded.base_dir : loaded.program_path.parent_path();
  // A job that came without a file (the service's) calls no subroutine files:
  // a request must not reach the daemon's file system.
  if (dir.empty()) return config;
  config.subroutine_loader = [dir](std::string_view name) -> std::unique_ptr<gcode::LineSource> {
    if (name.empty() || name.find_first_of("/\\") != std::string_view::npos ||
        name.find("..") != std::string_view::npos) {
      return nullptr;
    }
    auto in = std::make_unique<std::ifstream>(dir / (std::string(name) + ".ngc"), std::ios::binary);
    if (!*in) return nullptr;
    return gcode::makeStreamSource(std::move(in));
  };
  return config;
}

}  // namespace mdhd::cli

#pragma once
// Shadows of the real `mdhd modbus-sim` for the end-to-end tests: the example job
// as a shadow spec (program inline, default register map on the simulator's
// port), the simulator's port, and waiting for the machine to finish the program.
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "daemon/check_runner.h"
#include "daemon/shadow_session.h"
#include "sim/kinematics/joint_path.h"
#include "tests/modbus/sim_process.h"

namespace mdhd::shadow::testing {

using namespace std::chrono_literals;

inline const std::string kBin = MDHD_BIN;
inline std::string examplePath(const std::string& name) {
  return std::string(MDHD_SHARED_DIR) + "/examples/" + name + ".json";
}

inline int listeningPort(modbus_test::SimProcess& sim) {
  const std::string line = sim.readLine(10s);
  const std::string prefix = "listening on 127.0.0.1:";
  if (line.rfind(prefix, 0) != 0) return -1;
  return std::stoi(line.substr(prefix.size()));
}

// The example as a shadow would be asked for it: program text inline, the
// simulator's default map polled at `poll_hz`.
inline ShadowSpec exampleSpec(const cli::LoadedJob& loaded, int port, double poll_hz = 1000) {
  ShadowSpec spec;
  spec.job = loaded.job;
  std::ifstream in(loaded.program_path);
  std::ostringstream text;
  text << in.rdbuf();
  spec.job.program = text.str();
  spec.job.program_file.clear();
  spec.map = protocol::defaultModbusMap(*spec.job.machine);
  spec.map.port = port;
  spec.map.poll_hz = poll_hz;
  spec.map.timeout_ms = 200;
  return spec;
}

// Where and on which line the program's last motion ends.
struct FinalPose {
  gcode::AxisValues joints{};
  int line = 0;
};
inline FinalPose finalPose(const ShadowSpec& spec) {
  const kin::Kinematics kin(*spec.job.machine);
  const ProgramTrack track(spec.job, kin);
  const TrackedMotion& m = track.at(track.size() - 1);
  return {kin::JointPath(kin, m.motion, m.tool_length).endJoints(), m.motion.pos.line};
}

// Waits until the shadow has seen the machine at the end of the program and cut
// everything polled; false after `limit`.
inline bool waitFinished(const ShadowSession& session, const FinalPose& end,
                         std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  const kin::Machine& machine = *session.spec().job.machine;
  while (std::chrono::steady_clock::now() < deadline) {
    const nlohmann::json s = session.status();
    bool there = s["line"].is_number() && s["line"].get<int>() >= end.line;
    for (const kin::Joint& j : machine.joints) {
      const gcode::Axis a = *kin::axisOfName(j.name);
      there = there && std::abs(s["joints"][j.name].get<double>() - end.joints[a]) < 1e-3;
    }
    if (there)
      return session.waitIdle(std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now()));
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

}  // namespace mdhd::shadow::testing

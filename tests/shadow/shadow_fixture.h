#pragma once
// A 3-axis cell for the shadow tests: 40 x 40 x 20 stock at density 5, one flat
// end mill (cutter 10 mm, shank to 30, a 20 mm holder above), G43: Z joint = tip + 40.
#include <chrono>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "daemon/shadow_carver.h"
#include "daemon/shadow_session.h"
#include "sim/kinematics/presets.h"
#include "tests/check/check_fixture.h"

namespace mdhd::shadow::testing {

inline protocol::Job cellJob(std::optional<std::string> program = std::nullopt) {
  protocol::Job job;
  job.machine = kin::presets::threeAxisMill();
  job.tools.push_back(check::rig::flatTool());
  job.stock = {{0, 0, -20}, {40, 40, 0}};
  job.options.density = 5;
  job.program = std::move(program);
  return job;
}

// A sample at tip (x, y, z) of the cell's tool, `ms` milliseconds after t0.
inline PollSample at(double x, double y, double z, int ms, std::optional<std::int64_t> line = {},
                     std::optional<bool> spindle = true) {
  PollSample s;
  s.t = SteadyClock::time_point{} + std::chrono::milliseconds(ms);
  s.joints[gcode::kX] = x;
  s.joints[gcode::kY] = y;
  s.joints[gcode::kZ] = z + 40.0;
  s.tool = 1;
  s.spindle_on = spindle;
  s.line = line;
  return s;
}

// Registers of the cell's 3-axis default map (X Y Z float32 abcd, tool, spindle,
// line uint32): the tool's tip at (x, 20, z), `tool`, spindle on, line 7.
inline std::vector<std::uint16_t> defaultMapRegisters(float x, float z, std::uint16_t tool = 1) {
  const float xyz[3] = {x, 20.0f, z + 40.0f};
  std::vector<std::uint16_t> r;
  for (float v : xyz) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    r.push_back(static_cast<std::uint16_t>(bits >> 16));
    r.push_back(static_cast<std::uint16_t>(bits & 0xFFFF));
  }
  r.insert(r.end(), {tool, 1, 0, 7});
  return r;
}

// Waits until `s` is in `state`, at most `limit`; false when it never got there.
inline bool waitState(const ShadowSession& s, ShadowState state, std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (s.state() != state) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

}  // namespace mdhd::shadow::testing

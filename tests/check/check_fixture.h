#pragma once
// Runs a G-code program through a check::Simulation on a machine, for the tests.
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sim/check/simulation.h"
#include "sim/gcode/interpreter.h"
#include "sim/kinematics/inverse.h"
#include "sim/kinematics/presets.h"

namespace mdhd::check::rig {

struct Rig {
  kin::Machine machine = kin::presets::threeAxisMill();
  std::vector<geom::Tool> tools;
  geom::Aabb stock{{0, 0, -20}, {40, 40, 0}};
  std::vector<std::unique_ptr<geom::LineSolid>> fixtures;
  SimulationOptions options;
};

// A flat end mill: cutter to 10 mm above the tip, shank to 30, holder (20 mm) above.
inline geom::Tool flatTool(int number = 1) {
  geom::Tool t;
  t.number = number;
  t.shape = geom::ToolShape::kFlat;
  t.diameter = 6;
  t.shank_diameter = 6;
  t.flute_length = 10;
  t.length = 40;
  t.holder = {{20, 10}};
  return t;
}

// `inspect`, when given, sees the simulation after the report is made.
inline Report run(Rig setup, const std::string& program, const std::atomic<bool>* cancel = nullptr,
                  const std::function<void(const Simulation&)>& inspect = {}) {
  const kin::Kinematics kin(setup.machine);
  if (setup.tools.empty()) setup.tools.push_back(flatTool());
  Simulation sim(kin, setup.tools, setup.stock, std::move(setup.fixtures), setup.options);
  sim.setCancelFlag(cancel);
  gcode::InterpreterConfig config;
  config.home = setup.machine.home;
  config.axis_mask = 0;
  for (const kin::Joint& j : setup.machine.joints)
    if (const auto a = kin::axisOfName(j.name)) config.axis_mask |= 1u << *a;
  for (const geom::Tool& t : setup.tools) config.tools.add({t.number, t.length, t.diameter});
  config.tcp_switch = [&kin](const gcode::AxisValues& m, double length, bool to_tcp) {
    return kin::switchTcp(kin, m, length, to_tcp);
  };
  gcode::Interpreter interp(config, sim);
  interp.run(gcode::makeStringSource(program));
  Report report = sim.finish(static_cast<std::int64_t>(interp.blocksExecuted()));
  if (inspect) inspect(sim);
  return report;
}

// A G-code program written from a seeded generator, for the randomised tests:
// `rng` picks, uniform(lo, hi) draws a coordinate, `out` holds the text (fixed point,
// `digits` decimals).
struct RandomProgram {
  explicit RandomProgram(std::uint32_t seed, int digits) : rng(seed) {
    out.setf(std::ios::fixed);
    out.precision(digits);
  }
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
  }
  std::mt19937 rng;
  std::ostringstream out;
};

inline std::vector<const Collision*> ofType(const Report& r, CollisionType type) {
  std::vector<const Collision*> out;
  for (const Collision& c : r.collisions)
    if (c.type == type) out.push_back(&c);
  return out;
}

}  // namespace mdhd::check::rig

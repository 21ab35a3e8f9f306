// Run: build-kin/bin/bench_kinematics. Figures for docs/kinematics.md: the cost of
// one tool pose (FK) per machine layout, of the G43.4 solve and of a tcp path point.
#include <benchmark/benchmark.h>

#include "sim/kinematics/inverse.h"
#include "sim/kinematics/joint_path.h"
#include "sim/kinematics/limits.h"
#include "sim/kinematics/presets.h"

namespace mdhd::kin {
namespace {

Machine presetByIndex(int i) {
  switch (i) {
    case 0:
      return presets::threeAxisMill();
    case 1:
      return presets::acTrunnion();
    case 2:
      return presets::bcHeadTable();
    case 3:
      return presets::abHeadHead();
    default:
      return presets::nutatingB45();
  }
}

void toolPose(benchmark::State& state) {
  const Kinematics kin(presetByIndex(static_cast<int>(state.range(0))));
  state.SetLabel(kin.machine().name);
  JointValues q{10, 20, 30, -30, 25, 40, 0, 0, 0};
  for (auto _ : state) {
    q[gcode::kC] += 0.1;  // a new pose each time, as along a path
    benchmark::DoNotOptimize(kin.toolPose(q, 50));
  }
}
BENCHMARK(toolPose)->DenseRange(0, 4);

void solveTipBench(benchmark::State& state) {
  const Kinematics kin(presets::acTrunnion());
  JointValues q{0, 0, 0, -30, 0, 40, 0, 0, 0};
  glm::dvec3 tip{5, 6, 7};
  for (auto _ : state) {
    tip.x += 1e-3;
    benchmark::DoNotOptimize(solveTip(kin, tip, 50, q));
  }
}
BENCHMARK(solveTipBench);

void tcpPathPoint(benchmark::State& state) {
  const Kinematics kin(presets::bcHeadTable());
  gcode::Motion m;
  m.type = gcode::MotionType::kFeed;
  m.tcp = true;
  m.start = {0, 0, 10, 0, 0, 0, 0, 0, 0};
  m.end = {20, 10, 10, 0, 45, 90, 0, 0, 0};
  const JointPath path(kin, m, 50);
  double s = 0;
  for (auto _ : state) {
    s = s > 0.99 ? 0.01 : s + 1e-3;
    benchmark::DoNotOptimize(path.at(s));
  }
}
BENCHMARK(tcpPathPoint);

// A whole tcp move checked against limits it stays well inside (the common case).
void tcpPathLimits(benchmark::State& state) {
  const Kinematics kin(presets::bcHeadTable());
  gcode::Motion m;
  m.type = gcode::MotionType::kFeed;
  m.tcp = true;
  m.start = {0, 0, 10, 0, 0, 0, 0, 0, 0};
  m.end = {20, 10, 10, 0, 45, 30, 0, 0, 0};
  const JointPath path(kin, m, 50);
  for (auto _ : state) benchmark::DoNotOptimize(checkLimits(path));
}
BENCHMARK(tcpPathLimits);

}  // namespace
}  // namespace mdhd::kin

BENCHMARK_MAIN();

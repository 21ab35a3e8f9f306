// Random 5-axis programs on an AC trunnion (G43.4) cut with fresh regions (each step
// only where it reaches beyond the pose the last cut left the cutter held at) and
// without give the same report to the bit: the same removed volume, cells,
// collisions and overhang events. The programs mix turning rasters (A and C move with
// X, Y, Z), rasters with the axis held, turns in place, rapids into the stock, cuts
// with the spindle off and a tool change, so every way the chain of held poses is
// continued or broken is crossed.
#include <algorithm>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/check/check_fixture.h"
#include "tests/soak_seeds.h"

namespace mdhd::check {
namespace {

std::string randomFiveAxisProgram(std::uint32_t seed) {
  rig::RandomProgram w(seed, 4);
  w.out << "G21 G90 G17\nT1 M6\nM3 S9000\nG0 A-10 C0\nG43.4 H1\nG0 X-14 Y0 Z20\n";
  double a = -10.0, c = 0.0;
  int tool = 1;
  for (int block = 0; block < 10; ++block) {
    switch (w.rng() % 6) {
      case 0:
      case 1: {  // a turning raster: A and C move a little with every step
        const double y = w.uniform(-7, 7), depth = w.uniform(1.0, 3.0);
        const bool forward = w.rng() % 2 == 0;
        w.out << "G1 X" << (forward ? -12.0 : 12.0) << " Y" << y << " Z" << 10.0 - depth
              << " F900\n";
        for (int i = 0; i <= 30; ++i) {
          const double x = forward ? -12.0 + 0.8 * i : 12.0 - 0.8 * i;
          a = std::clamp(a + w.uniform(-0.4, 0.4), -25.0, 0.0);
          c += w.uniform(-0.5, 0.5);
          w.out << "G1 X" << x << " Y" << y + 0.3 * std::sin(x) << " Z"
                << 10.0 - depth + 0.5 * std::sin(0.5 * x) << " A" << a << " C" << c << "\n";
        }
        w.out << "G0 Z20\n";
        break;
      }
      case 2: {  // a raster with the axis held
        const double y = w.uniform(-7, 7), depth = w.uniform(1.0, 3.0);
        w.out << "G1 X-12 Y" << y << " Z" << 10.0 - depth << " F900\n";
        for (int i = 1; i <= 20; ++i)
          w.out << "G1 X" << -12.0 + 1.2 * i << " Z" << 10.0 - depth - 0.02 * i << "\n";
        w.out << "G0 Z20\n";
        break;
      }
      case 3: {  // a turn in place, in the material
        w.out << "G0 X" << w.uniform(-6, 6) << " Y" << w.uniform(-6, 6) << "\nG1 Z"
              << w.uniform(6, 9) << " F600\n";
        a = std::clamp(a + w.uniform(-6, 6), -25.0, 0.0);
        c += w.uniform(-20, 20);
        w.out << "G1 A" << a << " C" << c << " F1800\nG0 Z20\n";
        break;
      }
      case 4: {  // a rapid into the stock, or a cut with the spindle off
        const bool rapid = w.rng() % 2 == 0;
        if (!rapid) w.out << "M5\n";
        w.out << "G0 X" << w.uniform(-8, 8) << " Y" << w.uniform(-8, 8) << "\n"
              << (rapid ? "G0" : "G1 F300") << " Z" << w.uniform(8, 9.5) << "\n"
              << (rapid ? "G0" : "G1") << " X" << w.uniform(-8, 8) << "\nG0 Z20\n";
        if (!rapid) w.out << "M3 S9000\n";
        break;
      }
      default: {  // a tool change
        tool = 3 - tool;
        w.out << "G49\nG0 A" << a << " C" << c << "\nT" << tool << " M6\nG43.4 H" << tool
              << "\nG0 X-14 Y0 Z20\n";
        break;
      }
    }
  }
  w.out << "M30\n";
  return w.out.str();
}

Report runWith(const std::string& program, bool fresh, bool lazyCrossings = true) {
  rig::Rig s;
  s.options.lazy_crossings = lazyCrossings;
  s.machine = kin::presets::acTrunnion();
  s.stock = {{-10, -10, 0}, {10, 10, 10}};
  s.options.density = 5;
  s.options.batch_steps = 1;  // batches need fresh regions: compare step by step
  s.options.fresh_regions = fresh;
  geom::Tool ball = rig::flatTool(1);
  ball.shape = geom::ToolShape::kBall;
  s.tools = {ball, rig::flatTool(2)};
  return rig::run(std::move(s), program);
}

// The same collisions, to the bit: type, line and depth.
void expectSameCollisions(const Report& got, const Report& want) {
  ASSERT_EQ(got.collisions.size(), want.collisions.size());
  for (std::size_t i = 0; i < want.collisions.size(); ++i) {
    EXPECT_EQ(got.collisions[i].type, want.collisions[i].type) << i;
    EXPECT_EQ(got.collisions[i].line, want.collisions[i].line) << i;
    EXPECT_EQ(got.collisions[i].depth, want.collisions[i].depth) << i;
  }
}

class FreshRegions : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(FreshRegions, RandomFiveAxisProgramsGiveTheReportOfWholeCuts) {
  const std::string program = randomFiveAxisProgram(GetParam());
  const Report whole = runWith(program, false), fresh = runWith(program, true);
  EXPECT_GT(whole.stats.removed_volume_mm3, 50.0) << program;
  EXPECT_EQ(fresh.stats.removed_volume_mm3, whole.stats.removed_volume_mm3);
  EXPECT_EQ(fresh.mdh.leaves, whole.mdh.leaves);
  EXPECT_EQ(fresh.mdh.cells, whole.mdh.cells);
  EXPECT_EQ(fresh.overhang.events, whole.overhang.events);
  expectSameCollisions(fresh, whole);
}

// The turning steps are cut one by one with their crossings across z maps left
// pending (mdh::Stock::cut with a shared solid): the report of eager cuts to the bit,
// the motions' cutting times (from CutResult::removed) included.
TEST_P(FreshRegions, RandomFiveAxisProgramsGiveTheReportOfEagerCrossings) {
  const std::string program = randomFiveAxisProgram(GetParam());
  const Report eager = runWith(program, true, false), lazy = runWith(program, true, true);
  EXPECT_GT(eager.stats.removed_volume_mm3, 50.0) << program;
  EXPECT_EQ(lazy.stats.final_volume_mm3, eager.stats.final_volume_mm3);
  EXPECT_EQ(lazy.mdh.leaves, eager.mdh.leaves);
  EXPECT_EQ(lazy.mdh.embeddedSamples, eager.mdh.embeddedSamples);
  EXPECT_EQ(lazy.mdh.directions, eager.mdh.directions);
  EXPECT_EQ(lazy.overhang.events, eager.overhang.events);
  EXPECT_EQ(lazy.overhang.area_mm2, eager.overhang.area_mm2);
  ASSERT_EQ(lazy.stats.tools.size(), eager.stats.tools.size());
  // A tool may only rapid or cut air after its change (7 seeds of 1-400); not all do.
  double cutting = 0.0;
  for (std::size_t i = 0; i < eager.stats.tools.size(); ++i) {
    cutting += eager.stats.tools[i].cutting_time_s;
    EXPECT_EQ(lazy.stats.tools[i].cutting_time_s, eager.stats.tools[i].cutting_time_s) << i;
    EXPECT_EQ(lazy.stats.tools[i].removed_volume_mm3, eager.stats.tools[i].removed_volume_mm3);
  }
  EXPECT_GT(cutting, 0.0);
  expectSameCollisions(lazy, eager);
}

INSTANTIATE_TEST_SUITE_P(Seeds, FreshRegions, ::testing::ValuesIn(soak::seeds(4)));

}  // namespace
}  // namespace mdhd::check

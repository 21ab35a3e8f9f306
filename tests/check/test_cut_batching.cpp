// Random 3-axis programs cut with batched feed steps (the default) and one by one
// give the same report: the same collisions (type, lines, depth), cutting time,
// removed volume and cells. The programs mix short feed rasters over a wavy floor
// (the batches), arcs, plunges deep enough to bury the shank, rapids
// into the stock and cuts with the spindle off.
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/check/check_fixture.h"
#include "tests/soak_seeds.h"

namespace mdhd::check {
namespace {

std::string randomProgram(std::uint32_t seed) {
  rig::RandomProgram w(seed, 3);
  w.out << "G21 G90 G17\nT1 M6\nG43 H1\nM3 S9000\nG0 X5 Y5 Z5\n";
  for (int block = 0; block < 12; ++block) {
    switch (w.rng() % 5) {
      case 0:
      case 1: {  // a raster row of short feed steps over a wavy floor
        const double y = w.uniform(4, 36), depth = w.uniform(0.5, 3.0);
        const bool forward = w.rng() % 2 == 0;
        w.out << "G1 X" << (forward ? 4.0 : 36.0) << " Y" << y << " Z1 F800\n";
        for (int i = 0; i <= 40; ++i) {
          const double x = forward ? 4.0 + 0.8 * i : 36.0 - 0.8 * i;
          w.out << "G1 X" << x << " Z" << -depth + 0.6 * std::sin(0.4 * x + y) << "\n";
        }
        w.out << "G0 Z5\n";
        break;
      }
      case 2: {  // an arc at a random depth
        const double x = w.uniform(10, 30), y = w.uniform(10, 30), r = w.uniform(2, 6);
        w.out << "G0 X" << x + r << " Y" << y << "\nG1 Z" << -w.uniform(0.5, 4) << " F400\n"
              << "G3 X" << x - r << " Y" << y << " I" << -r << " J0\nG0 Z5\n";
        break;
      }
      case 3: {  // a plunge, deep enough now and then to bury the shank
        w.out << "G0 X" << w.uniform(5, 35) << " Y" << w.uniform(5, 35) << "\nG1 Z"
              << -w.uniform(1, 14) << " F300\nG1 X" << w.uniform(5, 35) << "\nG0 Z5\n";
        break;
      }
      default: {  // a rapid into the stock, or a cut with the spindle off
        const bool rapid = w.rng() % 2 == 0;
        if (!rapid) w.out << "M5\n";
        w.out << "G0 X" << w.uniform(5, 35) << " Y" << w.uniform(5, 35) << "\n"
              << (rapid ? "G0" : "G1 F300") << " Z" << -w.uniform(0.5, 2) << "\n"
              << (rapid ? "G0" : "G1") << " X" << w.uniform(5, 35) << "\nG0 Z5\n";
        if (!rapid) w.out << "M3 S9000\n";
        break;
      }
    }
  }
  w.out << "M30\n";
  return w.out.str();
}

Report runWith(const std::string& program, int batch, int brickZ, double chainTolerance = 0.0,
               double* machinedArea = nullptr, bool lazyCrossings = true) {
  rig::Rig s;
  s.options.lazy_crossings = lazyCrossings;
  s.options.density = 5;
  s.options.batch_steps = batch;
  s.options.brick_z = brickZ;
  s.options.chain_tolerance = chainTolerance;
  if (machinedArea != nullptr)
    return rig::run(std::move(s), program, nullptr,
                    [&](const Simulation& sim) { *machinedArea = sim.stock().area().total; });
  return rig::run(std::move(s), program);
}

class CutBatching : public ::testing::TestWithParam<std::uint32_t> {};

// The same collisions (type, first and last line) with depths within `depth`.
void expectSameCollisions(const Report& got, const Report& want, double depth) {
  ASSERT_EQ(got.collisions.size(), want.collisions.size());
  for (std::size_t i = 0; i < want.collisions.size(); ++i) {
    const Collision &a = got.collisions[i], &b = want.collisions[i];
    EXPECT_EQ(a.type, b.type) << i;
    EXPECT_EQ(a.line, b.line) << i;
    EXPECT_EQ(a.last_line, b.last_line) << i;
    EXPECT_NEAR(a.depth, b.depth, depth) << i;
  }
}

// A batch is cut as one union when every cell it reaches keeps its direction. One by
// one, a step may leave a transient overhang that a later step of the same batch
// removes (a plunge burying the shank, then a cut above it): the slow path then splits
// or turns cells the batch never touches, and the maps differ by their discretisation.
// Collisions and volumes agree in every brick shape; with cubic bricks these programs
// also meet no transient overhang, so the cells agree exactly there.
void expectSameReport(const std::string& program, int brickZ) {
  const Report one = runWith(program, 1, brickZ), batched = runWith(program, 16, brickZ);
  EXPECT_GT(one.stats.removed_volume_mm3, 100.0);
  expectSameCollisions(batched, one, 1e-6);
  for (std::size_t i = 0; i < one.collisions.size() && i < batched.collisions.size(); ++i)
    EXPECT_NEAR(batched.collisions[i].path_s, one.collisions[i].path_s, 1e-9) << i;
  ASSERT_EQ(batched.stats.tools.size(), one.stats.tools.size());
  for (std::size_t i = 0; i < one.stats.tools.size(); ++i) {
    EXPECT_NEAR(batched.stats.tools[i].cutting_time_s, one.stats.tools[i].cutting_time_s, 1e-9);
    EXPECT_NEAR(batched.stats.tools[i].removed_volume_mm3, one.stats.tools[i].removed_volume_mm3,
                1e-5 * one.stats.removed_volume_mm3);
  }
  EXPECT_NEAR(batched.stats.removed_volume_mm3, one.stats.removed_volume_mm3,
              1e-5 * one.stats.removed_volume_mm3);
  EXPECT_EQ(batched.overhang.first_line, one.overhang.first_line);
  if (brickZ == -1) {
    EXPECT_NEAR(batched.stats.removed_volume_mm3, one.stats.removed_volume_mm3,
                1e-6 * one.stats.removed_volume_mm3);
    EXPECT_EQ(batched.mdh.leaves, one.mdh.leaves);
    EXPECT_EQ(batched.overhang.events, one.overhang.events);
  }
}

TEST_P(CutBatching, RandomProgramsGiveTheReportOfOneByOne) {
  const std::string program = randomProgram(GetParam());
  for (int brickZ : {-1, 0}) {
    SCOPED_TRACE(brickZ == -1 ? "cubic bricks" : "bricks as tall as the stock");
    expectSameReport(program, brickZ);
  }
}

// Lazy crossings (mdh::StockOptions::lazy_crossings) are the engine's business too: the
// batches leave the stock, and so the report, of the eager cuts to the bit (collisions,
// depths, times, volumes, overhang area, cells, embedded samples).
TEST_P(CutBatching, LazyCrossingsGiveTheReportOfEagerOnes) {
  const std::string program = randomProgram(GetParam());
  for (int brickZ : {-1, 0}) {
    SCOPED_TRACE(brickZ == -1 ? "cubic bricks" : "bricks as tall as the stock");
    const Report lazy = runWith(program, 16, brickZ, -1.0);
    const Report eager = runWith(program, 16, brickZ, -1.0, nullptr, false);
    expectSameCollisions(lazy, eager, 0.0);
    ASSERT_EQ(lazy.stats.tools.size(), eager.stats.tools.size());
    for (std::size_t i = 0; i < eager.stats.tools.size(); ++i) {
      EXPECT_EQ(lazy.stats.tools[i].tool, eager.stats.tools[i].tool);
      EXPECT_EQ(lazy.stats.tools[i].cutting_time_s, eager.stats.tools[i].cutting_time_s);
      EXPECT_EQ(lazy.stats.tools[i].removed_volume_mm3, eager.stats.tools[i].removed_volume_mm3);
    }
    EXPECT_EQ(lazy.stats.final_volume_mm3, eager.stats.final_volume_mm3);
    EXPECT_EQ(lazy.overhang.area_mm2, eager.overhang.area_mm2);
    EXPECT_EQ(lazy.overhang.events, eager.overhang.events);
    EXPECT_EQ(lazy.mdh.leaves, eager.mdh.leaves);
    EXPECT_EQ(lazy.mdh.embeddedSamples, eager.mdh.embeddedSamples);
  }
}

// The bricks' shape is the engine's business: bricks as tall as the stock (a 3-axis
// machine's default) give the report of cubic ones, up to the maps' discretisation
// where the shank buries the flutes and cells turn or split differently.
TEST_P(CutBatching, BricksAsTallAsTheStockGiveTheReportOfCubes) {
  const std::string program = randomProgram(GetParam());
  const Report cubes = runWith(program, 16, -1), tall = runWith(program, 16, 0);
  EXPECT_LT(tall.mdh.cells, cubes.mdh.cells);
  expectSameCollisions(tall, cubes, 1e-6);
  // Seeds 1 and 2 differ by 0.03 % and 0.002 % (removed volume, density 5), where density
  // 5 itself is 0.1 % from density 20 (either shape): the maps' discretisation.
  EXPECT_NEAR(tall.stats.removed_volume_mm3, cubes.stats.removed_volume_mm3,
              5e-4 * cubes.stats.removed_volume_mm3);
  EXPECT_EQ(tall.overhang.first_line, cubes.overhang.first_line);
}

// A batch's chain less the points Douglas-Peucker drops within half the job's
// tolerance (the default): the swept volumes stay within that distance of the
// steps', so the removed volume differs by at most that much times the machined
// surface; the collisions are found on the steps themselves (the same ones, at the
// same lines), their depths into a stock whose surface moved by at most that much.
TEST_P(CutBatching, ChainsWithinHalfTheToleranceStayWithinItOfTheSteps) {
  const std::string program = randomProgram(GetParam());
  const double tolerance = SimulationOptions{}.tolerance / 2;
  double area = 0.0;
  const Report exact = runWith(program, 16, -1, 0.0, &area);
  const Report chained = runWith(program, 16, -1, -1.0);
  // Depths are measured into the stock, whose surface the chains moved by <= tolerance.
  expectSameCollisions(chained, exact, tolerance);
  EXPECT_GT(area, 100.0);
  EXPECT_NEAR(chained.stats.removed_volume_mm3, exact.stats.removed_volume_mm3, tolerance * area);
  EXPECT_EQ(chained.stats.moves.total(), exact.stats.moves.total());
}

TEST(BrickShape, TallOnlyWhereNoRotaryJointTurnsTheTool) {
  // An empty program leaves the bricks as they were laid: 40 x 40 x 20 mm at 10/mm in
  // bricks of 32 grid cubes is 13 x 13 columns of bricks, 7 high unless tall.
  rig::Rig three;
  EXPECT_EQ(rig::run(std::move(three), "M30\n").mdh.leaves, 13 * 13);
  rig::Rig five;
  five.machine = kin::presets::acTrunnion();
  EXPECT_EQ(rig::run(std::move(five), "M30\n").mdh.leaves, 13 * 13 * 7);
  rig::Rig forced;
  forced.options.brick_z = -1;
  EXPECT_EQ(rig::run(std::move(forced), "M30\n").mdh.leaves, 13 * 13 * 7);
  // 40 mm tall (400 levels): flutes of 10 mm could leave an overhang under a buried
  // shank, so bricks stop at 256 levels; flutes of 40 mm cut whole columns.
  rig::Rig shortFlutes;
  shortFlutes.stock = {{0, 0, -40}, {40, 40, 0}};
  EXPECT_EQ(rig::run(std::move(shortFlutes), "M30\n").mdh.leaves, 13 * 13 * 2);
  rig::Rig longFlutes;
  longFlutes.stock = {{0, 0, -40}, {40, 40, 0}};
  longFlutes.tools.push_back(rig::flatTool());
  longFlutes.tools.back().flute_length = 40;
  longFlutes.tools.back().length = 80;
  EXPECT_EQ(rig::run(std::move(longFlutes), "M30\n").mdh.leaves, 13 * 13);
}

INSTANTIATE_TEST_SUITE_P(Seeds, CutBatching, ::testing::ValuesIn(soak::seeds(6)));

}  // namespace
}  // namespace mdhd::check

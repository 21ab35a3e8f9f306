// Random 3-axis programs cut with batched feed steps (the default) and one by one
// give the same report: the same collisions (type, lines, depth), cutting time,
// removed volume and cells. The programs mix short feed rasters over a wavy floor
// (the batches), arcs, plunges deep enough to bury the shank, rapids
// into the stock and cuts with the spindle off.
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

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

struct Kept {
  Report report;
  std::unique_ptr<mdh::Stock> stock;
  double machinedArea = 0.0;
};

Kept runKeeping(const std::string& program, int batch, int brickZ) {
  rig::Rig s;
  s.options.density = 5;
  s.options.batch_steps = batch;
  s.options.brick_z = brickZ;
  s.options.chain_tolerance = 0.0;
  Kept k;
  k.report = rig::run(std::move(s), program, nullptr, [&](const Simulation& sim) {
    k.stock = sim.stock().clone();
    k.machinedArea = sim.stock().area().total;
  });
  return k;
}

// Every grid line of the two stocks holds as many solid intervals, their ends within
// `tolerance` mm. Lines of every third row and column, each axis: a wall or floor
// that differs spans several.
void expectSameSamples(const mdh::Stock& got, const mdh::Stock& want, double tolerance) {
  const mdh::GridSpec& g = want.grid();
  std::vector<geom::Interval> a, b;
  int lines = 0, moved = 0;
  double worst = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int iu = 0; iu <= g.cubes[u]; iu += 3)
      for (int iv = 0; iv <= g.cubes[v]; iv += 3) {
        a.clear();
        b.clear();
        got.solidIntervals(axis, iu, iv, a);
        want.solidIntervals(axis, iu, iv, b);
        ++lines;
        ASSERT_EQ(a.size(), b.size()) << "axis " << axis << " line " << iu << " " << iv;
        double d = 0.0;
        for (std::size_t k = 0; k < a.size(); ++k)
          d = std::max({d, std::abs(a[k].lo - b[k].lo), std::abs(a[k].hi - b[k].hi)});
        moved += d > 0.0;
        worst = std::max(worst, d);
      }
  }
  EXPECT_LE(worst, tolerance) << moved << " of " << lines << " lines moved";
}

// A batch is cut as one union when every cell it reaches keeps its direction. One by
// one, a step may leave a transient overhang that a later step of the same batch
// removes (a plunge burying the shank, then a cut above it): the slow path then splits
// or turns cells the batch never touches. The two stocks hold the same samples: every
// grid line the same solid intervals, an end moved at most a grid spacing (an edge
// cut from both ends keeps one crossing per level, which the steps and their union
// may place anywhere in the edge: up to 0.12 h on 1-2 % of the lines, 0.98 h on 2 of
// 9045 in seed 176, over seeds 1-400), so the collisions are the same. Volumes
// integrate each cell's surface between its lines in the cell's own direction: where
// cells turned differently they differ by the maps' discretisation (seed 53: a 10 x 6
// mm wall between two rows of columns, in a +x map one way and a +y map the other,
// 1.3e-3 of the removed volume), bounded here by a twentieth of a grid spacing over
// the machined surface. The grid lines' own trapezoid sums along x, y and z spread as
// far (0.041 h over the surface, seed 322).
void expectSameReport(const std::string& program, int brickZ) {
  const Kept one = runKeeping(program, 1, brickZ), batched = runKeeping(program, 16, brickZ);
  const double h = 1.0 / 5, volumeTolerance = 0.05 * h * one.machinedArea;
  EXPECT_GT(one.report.stats.removed_volume_mm3, 100.0);
  expectSameCollisions(batched.report, one.report, 1e-6);
  for (std::size_t i = 0; i < one.report.collisions.size() && i < batched.report.collisions.size();
       ++i)
    EXPECT_NEAR(batched.report.collisions[i].path_s, one.report.collisions[i].path_s, 1e-9) << i;
  ASSERT_EQ(batched.report.stats.tools.size(), one.report.stats.tools.size());
  for (std::size_t i = 0; i < one.report.stats.tools.size(); ++i) {
    EXPECT_NEAR(batched.report.stats.tools[i].cutting_time_s,
                one.report.stats.tools[i].cutting_time_s, 1e-9);
    EXPECT_NEAR(batched.report.stats.tools[i].removed_volume_mm3,
                one.report.stats.tools[i].removed_volume_mm3, volumeTolerance);
  }
  EXPECT_NEAR(batched.report.stats.removed_volume_mm3, one.report.stats.removed_volume_mm3,
              volumeTolerance);
  EXPECT_EQ(batched.report.overhang.first_line, one.report.overhang.first_line);
  expectSameSamples(*batched.stock, *one.stock, h);
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
// machine's default) hold the samples of cubic ones, and so their collisions, with
// the volume up to the maps' discretisation where the shank buries the flutes and
// cells turn or split differently (as expectSameReport above; 0.027 h over the machined
// surface, 3.8e-3 of the removed volume, in seed 322 of 1-400).
TEST_P(CutBatching, BricksAsTallAsTheStockGiveTheReportOfCubes) {
  const std::string program = randomProgram(GetParam());
  const Kept cubes = runKeeping(program, 16, -1), tall = runKeeping(program, 16, 0);
  const double h = 1.0 / 5;
  EXPECT_LT(tall.report.mdh.cells, cubes.report.mdh.cells);
  expectSameCollisions(tall.report, cubes.report, 1e-6);
  EXPECT_NEAR(tall.report.stats.removed_volume_mm3, cubes.report.stats.removed_volume_mm3,
              0.05 * h * cubes.machinedArea);
  EXPECT_EQ(tall.report.overhang.first_line, cubes.report.overhang.first_line);
  expectSameSamples(*tall.stock, *cubes.stock, h);
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

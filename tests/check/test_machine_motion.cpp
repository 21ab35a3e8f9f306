// The live-shadow entries of the simulation: a machine's joint-space move with a
// known duration (machineMotion), a fork that runs ahead on a copy of the stock,
// a snapshot report while the run goes on, and where on its motion an episode began.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sim/kinematics/joint_path.h"
#include "tests/check/check_fixture.h"

namespace mdhd::check {
namespace {

using rig::flatTool;

using std::numbers::pi;

// Collects a program's motions.
class Recorder : public gcode::MotionSink {
 public:
  void motion(const gcode::Motion& m) override {
    motions.push_back(m);
    motions.back().block_text = nullptr;
  }
  std::vector<gcode::Motion> motions;
};

std::vector<gcode::Motion> interpret(const kin::Machine& machine, const std::string& program) {
  Recorder rec;
  gcode::InterpreterConfig config;
  config.home = machine.home;
  config.axis_mask = kin::axisMask(machine);
  const geom::Tool t = flatTool();
  config.tools.add({t.number, t.length, t.diameter});
  gcode::Interpreter(config, rec).run(gcode::makeStringSource(program));
  return rec.motions;
}

// A straight joint-space move as a shadow builds it from two polls.
gcode::Motion jointMove(const gcode::Motion& like, const gcode::AxisValues& from,
                        const gcode::AxisValues& to) {
  gcode::Motion m;
  m.type =
      like.type == gcode::MotionType::kRapid ? gcode::MotionType::kRapid : gcode::MotionType::kFeed;
  m.pos = like.pos;
  m.start = from;
  m.end = to;
  m.tool = like.tool;
  m.spindle = like.spindle;
  return m;
}

struct Cell {
  kin::Machine machine = kin::presets::threeAxisMill();
  kin::Kinematics kin{machine};
  std::vector<geom::Tool> tools{flatTool()};
  SimulationOptions options;
  Cell() { options.density = 5; }
  std::unique_ptr<Simulation> make() const {
    return std::make_unique<Simulation>(kin, tools, geom::Aabb{{0, 0, -20}, {40, 40, 0}},
                                        std::vector<std::unique_ptr<geom::LineSolid>>{}, options);
  }
};

const std::string kPocket =
    "G21 G90 G17\nT1 M6\nG43 H1\nM3 S9000\n"  // 1-4
    "G0 X10 Y10 Z5\n"                         // 5
    "G1 Z-3 F300\n"                           // 6
    "G1 X30 F600\n"                           // 7
    "G2 X30 Y30 I0 J10\n"                     // 8: a half circle
    "G1 X10\n"                                // 9
    "G0 Z5\nM5\nM30\n";

TEST(MachineMotion, StraightJointMovesCutAsTheProgramDoes) {
  const Cell cell;
  const auto motions = interpret(cell.machine, kPocket);
  auto program = cell.make();
  auto live = cell.make();
  for (const gcode::Motion& m : motions) {
    if (m.type == gcode::MotionType::kArc) break;
    program->motion(m);
    program->flushCuts();  // a program's run batches its feed steps' cuts
    live->machineMotion(jointMove(m, m.start, m.end), 0.5);
    EXPECT_DOUBLE_EQ(live->stock().volume(), program->stock().volume()) << m.pos.line;
  }
  EXPECT_LT(program->stock().volume(), 40 * 40 * 20 - 20 * 6 * 3);
}

TEST(MachineMotion, PolledArcMatchesTheArcWithinTheChordError) {
  const Cell cell;
  const auto motions = interpret(cell.machine, kPocket);
  auto program = cell.make();
  auto live = cell.make();
  double seconds = 0.0;
  for (const gcode::Motion& m : motions) {
    program->motion(m);
    // The arc as a machine polled at 100 points shows it: straight joint moves.
    const kin::JointPath path(cell.kin, m, flatTool().length);
    const int polls = m.type == gcode::MotionType::kArc ? 100 : 1;
    gcode::AxisValues q = path.at(0.0);
    for (int i = 1; i <= polls; ++i) {
      const gcode::AxisValues next = path.at(double(i) / polls);
      live->machineMotion(jointMove(m, q, next), 0.01);
      seconds += 0.01;
      q = next;
    }
  }
  const Report a = program->finish(0);
  const Report b = live->finish(0);
  EXPECT_TRUE(a.collisions.empty());
  EXPECT_TRUE(b.collisions.empty());
  // Chords of 10 * pi / 100 mm on a 10 mm radius: a sagitta of 1.2 um.
  EXPECT_NEAR(b.stats.removed_volume_mm3, a.stats.removed_volume_mm3,
              1e-3 * a.stats.removed_volume_mm3);
  EXPECT_GT(a.stats.removed_volume_mm3, 3 * (20 * 6 + pi * 10 * 6));
  EXPECT_NEAR(b.stats.cycle_time_s, seconds, 1e-9);  // the machine's time, not the program's
}

TEST(MachineMotion, RapidIntoStockIsFoundOnAJointMoveWithItsShareOfThePath) {
  const Cell cell;
  auto live = cell.make();
  gcode::Motion like;
  like.type = gcode::MotionType::kRapid;
  like.pos.line = 7;
  like.tool = 1;
  like.spindle = gcode::SpindleState::kClockwise;
  gcode::AxisValues above{}, below{};
  above[gcode::kX] = below[gcode::kX] = 20;
  above[gcode::kY] = below[gcode::kY] = 20;
  above[gcode::kZ] = 40 + 6;  // tip 6 mm above the stock (G43: Z joint = tip + 40)
  below[gcode::kZ] = 40 - 2;  // 2 mm into it
  live->machineMotion(jointMove(like, above, below), 0.02);
  ASSERT_EQ(live->collisions().size(), 1u);
  const Collision& c = live->collisions()[0];
  EXPECT_EQ(c.type, CollisionType::kRapidIntoStock);
  EXPECT_EQ(c.line, 7);
  EXPECT_NEAR(c.path_s, 6.0 / 8.0, 0.15 / 8.0);  // contact at the top: 6 of the 8 mm
  EXPECT_NEAR(c.depth, 2.0, 0.2);

  // A fork goes on with the episode: the same rapid on sideways is no new contact.
  auto ahead = live->fork();
  ASSERT_EQ(ahead->collisions().size(), 1u);
  gcode::AxisValues side = below;
  side[gcode::kX] += 4;
  ahead->machineMotion(jointMove(like, below, side), 0.01);
  EXPECT_EQ(ahead->collisions().size(), 1u);
  EXPECT_EQ(ahead->collisions()[0].last_line, 7);
  EXPECT_EQ(live->collisions().size(), 1u);
}

TEST(MachineMotion, ForkRunsAheadOnACopyAndSnapshotMatchesFinish) {
  const Cell cell;
  const auto motions = interpret(cell.machine, kPocket);
  auto live = cell.make();
  for (std::size_t i = 0; i < 3; ++i) live->motion(motions[i]);  // lines 5, 6, 7
  EXPECT_THROW(live->snapshot(7), std::logic_error);             // line 7's cut is still batched
  live->flushCuts();
  const double volume = live->stock().volume();
  const Report snap = live->snapshot(7);
  EXPECT_EQ(snap.stats.blocks, 7);
  EXPECT_DOUBLE_EQ(snap.stats.final_volume_mm3, volume);
  EXPECT_GT(snap.stats.removed_volume_mm3, 20 * 6 * 3);

  // A fork rapids into the uncut stock: the fork cuts and alarms, the original
  // does neither.
  auto ahead = live->fork();
  EXPECT_DOUBLE_EQ(ahead->stock().volume(), volume);
  EXPECT_TRUE(ahead->collisions().empty());
  gcode::Motion rapid = motions[0];  // G0 X10 Y10 Z5, now down to 2 mm deep at X35 Y35
  rapid.start = motions[0].end;
  rapid.start[gcode::kX] = rapid.start[gcode::kY] = 35;
  rapid.end = rapid.start;
  rapid.end[gcode::kZ] -= 7;
  rapid.pos.line = 42;
  ahead->motion(rapid);
  ASSERT_EQ(ahead->collisions().size(), 1u);
  EXPECT_EQ(ahead->collisions()[0].type, CollisionType::kRapidIntoStock);
  EXPECT_EQ(ahead->collisions()[0].line, 42);
  EXPECT_NEAR(ahead->stock().volume(), volume - pi * 9 * 2, 0.03 * pi * 9 * 2);
  EXPECT_DOUBLE_EQ(live->stock().volume(), volume);
  EXPECT_TRUE(live->collisions().empty());

  for (std::size_t i = 3; i < motions.size(); ++i) live->motion(motions[i]);
  live->flushCuts();
  const Report again = live->snapshot(12);
  const Report done = live->finish(12);
  EXPECT_DOUBLE_EQ(again.stats.final_volume_mm3, done.stats.final_volume_mm3);
  EXPECT_DOUBLE_EQ(again.overhang.area_mm2, done.overhang.area_mm2);
  EXPECT_EQ(again.mdh.leaves, done.mdh.leaves);
  EXPECT_EQ(again.status, Status::kClean);
}

}  // namespace
}  // namespace mdhd::check

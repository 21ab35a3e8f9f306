#pragma once
// The pre-run check as one streaming MotionSink: every interpreted motion becomes
// a joint path, the path tool poses in W, the poses swept volumes of cutter, shank
// and holder; the cutter's sweep cuts the stock, the others probe it and the
// fixtures. Out come collision episodes and statistics (a Report). Nothing of a
// motion is kept after it, so a program of any length runs in bounded memory.
//
//   Simulation sim(kin, tools, stock_box, fixtures, options);
//   gcode::Interpreter(config, sim).run(source);
//   Report report = sim.finish(interp.blocksExecuted());
#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "sim/check/contact_depth.h"
#include "sim/check/cut_batch.h"
#include "sim/check/episodes.h"
#include "sim/check/motion_steps.h"
#include "sim/check/report.h"
#include "sim/geometry/line_solid.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool.h"
#include "sim/geometry/tool_part.h"
#include "sim/geometry/tool_pose.h"
#include "sim/kinematics/kinematics.h"
#include "sim/mdh/stock.h"

namespace mdhd::check {

struct SimulationOptions {
  double density = 10.0;  // grid points per mm
  int steps = 0;          // pieces per move; 0: adaptive to `tolerance`
  double tolerance = 0.01;
  std::vector<mdh::Rule> ruleset{mdh::Rule::kFEFS_FFS, mdh::Rule::kCTD, mdh::Rule::kSPT,
                                 mdh::Rule::kRS};
  std::uint64_t seed = 1;
  bool three_way = true;
  bool two_sided = true;            // mdh::StockOptions::two_sided
  double contact_tolerance = -1.0;  // < 0: half the grid spacing
  int threads = 1;                  // stock cutting threads (0: hardware concurrency)
  // Feed steps translating one cutter along a chain are cut up to this many at once
  // (cut_batch.h; 1: one by one): the same report up to the map's resolution (rarely a
  // crossing placed elsewhere inside its grid edge).
  int batch_steps = 24;  // 16 before session 15 (docs/check.md, "Session 15")
  // A batch's chain drops the points between straight feed steps that stay within this
  // many mm of the chain that replaces them (check/cut_batch.h): < 0 half of
  // `tolerance`, 0 none (every batch the stock the steps one by one would leave).
  double chain_tolerance = -1.0;
  // Each step cuts only where it reaches beyond the pose the last cut left the cutter
  // held at (geom::freshRegion): the same stock to the bit. false: the whole box of
  // every sweep (for tests and benchmarks; no batches then).
  bool fresh_regions = true;
  // The stock's bricks along z (mdh::StockOptions::brick_z): kBrickZAuto takes the
  // stock's height on a machine without rotary joints (the tool only ever cuts from
  // above, so the maps stay +z) when every tool's flutes are as long as the stock is
  // tall, bricks of kBrickZCap levels there otherwise (a buried shank can leave an
  // overhang, and a taller cell costs its height to unpack and to answer lines across
  // it), and cubes on a machine with rotary joints.
  static constexpr int kBrickZAuto = -2;
  static constexpr int kBrickZCap = 256;
  int brick_z = kBrickZAuto;
  // Batched cuts leave the crossings across z maps to be computed when needed
  // (mdh::StockOptions::lazy_crossings): the same report to the bit; false for comparing.
  bool lazy_crossings = true;
};

// Thrown out of motion() when the cancel flag is raised; the interpreter passes it on.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("check cancelled") {}
};

class Simulation final : public gcode::MotionSink {
 public:
  // `kin` must outlive the simulation. Throws std::invalid_argument for a stock the
  // grid cannot hold or a tool that is not buildable.
  Simulation(const kin::Kinematics& kin, const std::vector<geom::Tool>& tools,
             const geom::Aabb& stock, std::vector<std::unique_ptr<geom::LineSolid>> fixtures,
             SimulationOptions options);
  ~Simulation() override;
  // Why the constructor would refuse this stock (a grid too fine for the engine), or
  // empty: lets a service refuse a job when it is submitted rather than when it runs.
  static std::string stockProblem(const kin::Machine& machine, const std::vector<geom::Tool>& tools,
                                  const geom::Aabb& stock, const SimulationOptions& options);

  // Throws gcode::GcodeError at the motion's place when it cannot be simulated (a
  // singular tool-centre-point pose, a half-turn of the tool axis within one fixed
  // step, a tool too thin for any of its contacts to be told: blindReason), Cancelled
  // when cancelled. A spindle turned on at 0 rpm (M3 S0, or no S ever) counts as off.
  void motion(const gcode::Motion& m) override;
  void event(const gcode::Event& e) override;

  // A motion whose machine time is known rather than programmed (a live machine's
  // move between two polls, m.feed unused): checked and cut exactly as motion(m),
  // `seconds` added to the cycle time. Same exceptions as motion(), except that a
  // thin tool is cut all the same (the machine moves it anyway; the stock must follow).
  void machineMotion(const gcode::Motion& m, double seconds);

  // Why no contact of `tool` could pass the contact tolerance (its cutter or shank is
  // no wider than twice it), or "" (also for an unknown tool).
  const std::string& blindReason(int tool) const;

  // A copy to run ahead of this one (a look-ahead): the same machine, tools, fixtures
  // and options, a deep copy of the stock as it is now, the current tool and the
  // collision episodes so far (a contact going on is not new to the copy), fresh
  // statistics. `kin` and the fixtures are shared read-only, so the copy may run on
  // another thread while this one goes on. Throws std::logic_error while cuts are
  // batched (after motion(): flushCuts() first).
  std::unique_ptr<Simulation> fork() const;

  // Called after every motion with its place and the number of motions so far.
  void setProgress(std::function<void(const gcode::SourcePos&, std::int64_t)> progress) {
    progress_ = std::move(progress);
  }
  // Called the moment a contact opens a collision episode, before its depth is
  // measured in full: collisions()[episode] then holds a first bound of its depth
  // (over the contact tolerance) and its place within 1/16 of a step (path_s,
  // joints, position); the same step refines both to what they are without a
  // listener right after (the same bisection carried on, the full depth measure).
  // With a listener a new contact costs one early-out depth pass more; the report
  // is the same. Forks do not inherit it.
  void setContactListener(std::function<void(std::size_t episode)> listener) {
    contact_listener_ = std::move(listener);
  }
  // Checked at every step; raising it makes motion() throw Cancelled promptly.
  void setCancelFlag(const std::atomic<bool>* cancel) { cancel_ = cancel; }

  // Closes the run: volumes, stock statistics, overhang area. `blocks`: the
  // interpreter's count. Call once, after the program.
  Report finish(std::int64_t blocks);

  // The report as it would be if the run ended now (a live shadow's): the same as
  // finish() but leaves the run going. Walks the stock: not for every motion.
  // Throws std::logic_error while cuts are batched, as fork().
  Report snapshot(std::int64_t blocks) const;

  // Collision episodes so far, in order of their start; the last ones may still
  // be deepening.
  const std::vector<Collision>& collisions() const { return episodes_.collisions(); }

  // After motion() the last steps' cuts may still be batched: flushCuts() makes
  // them (machineMotion() and finish() do). stock() throws std::logic_error until
  // then, rather than show a stock that lags the program.
  const mdh::Stock& stock() const {
    requireFlushed("stock");
    return *stock_;
  }
  void flushCuts();
  const CutBatchStats& cutBatchStats() const { return batch_.stats(); }
  double contactTolerance() const { return contact_tolerance_; }

 private:
  // A ball holding a tool part wherever its tip and axis are: centred `height` up the
  // axis from the tip, of radius `radius` (none for an empty part).
  struct PartBall {
    double height = 0.0, radius = -1.0;
  };
  struct ToolParts {
    geom::Tool tool;
    geom::ToolPart cutter, shank, holder;
    double reach = 0.0;
    PartBall shankBall, holderBall;
    // Why no contact of this tool could be reported (blindTo), "" when it can.
    std::string blind;
  };
  struct Step;
  struct ForkTag {};
  Simulation(const Simulation& from, ForkTag);

  void simulate(const gcode::Motion& m, const double* seconds);
  const ToolParts* partsFor(int tool);
  void checkLimits(const gcode::Motion& m, const kin::JointPath& path);
  void runStep(const gcode::Motion& m, const kin::JointPath& path, const ToolParts* parts,
               const StepPose& a, const StepPose& b, bool& removed);
  void cutterStep(const Step& step, bool& removed);
  // Books the removal of the tool that cut until now (if it did) and starts `next`'s.
  void closeToolRemoval(int next);
  // Books a cut's removal and overhang events against the motion at `line`.
  void noteCut(const mdh::CutResult& r, int line);
  // How far any point of `part` moves over the step along the chord (the tip's move
  // plus the axis's turn times the part's reach).
  static double chordTravel(const Step& step, const geom::ToolPart& part);
  // A depth no measure of `part` needs to look past (contact's `enough`).
  double deepEnough(const geom::ToolPart& part) const;
  // Whether the open episode of `key` may skip this step's measure (adds the step's
  // travel to it): its part moved less than a grid spacing since the last measure, or
  // it is as deep as the part allows.
  bool measureCanWait(const EpisodeKey& key, const Step& step, const geom::ToolPart& part);
  // Records the stock's z lines under `sweep` that this motion has not recorded yet:
  // taken before a rapid's (or spindle-off) step cuts, they are the material the motion
  // met, which its depth is measured against.
  void keepMaterialBefore(const geom::SweptVolume& sweep);
  void stockContacts(const Step& step);
  void fixtureContacts(const Step& step);
  Collision entry(const Step& step, CollisionType type, double f) const;
  struct Bracket;
  using Touches = std::function<bool(const geom::SweptVolume&)>;
  Penetration contact(const Step& step, const EpisodeKey& key, const geom::ToolPart& part,
                      const Touches& touches,
                      const std::function<Penetration(double enough)>& measure);
  double firstContact(const Step& step, const geom::ToolPart& part, const Touches& touches,
                      Bracket& bracket, int bisections) const;
  geom::SweptVolume sweep(const Step& step, const geom::ToolPart& part, double f) const;
  geom::SweptVolume sweep(const geom::ToolPose& a, const geom::ToolPose& end,
                          const geom::ToolPart& part) const;
  // Whether a contact check needs `part`'s sweep over the step a -> b: there are
  // fixtures, the axis turns, or the ball holding the part comes within reach of the
  // stock's box (material never leaves it).
  bool mayTouchStock(const PartBall& ball, const geom::ToolPose& a, const geom::ToolPose& b) const;
  void checkCancel() const;
  void requireFlushed(const char* what) const;

  // The z lines (key: ix | iy << 32) as they were before the current motion's cutter
  // met them in a rapid or with the spindle off (keepMaterialBefore); cleared per motion.
  std::unordered_map<std::uint64_t, std::vector<geom::Interval>> material_before_;
  std::size_t material_before_intervals_ = 0;

  const kin::Kinematics& kin_;
  std::map<int, ToolParts> tools_;
  std::unique_ptr<mdh::Stock> stock_;
  // Shared with forks, never changed after construction.
  std::shared_ptr<const std::vector<std::unique_ptr<geom::LineSolid>>> fixtures_;
  SimulationOptions options_;
  double contact_tolerance_ = 0.0;
  int current_tool_ = -1;
  // The pose the last cut left its cutter held at (a translation's end pose, a
  // turning step's last in-between pose), and which cutter: a step from there only
  // needs the stock where it reaches beyond that pose (geom::freshRegion). Not
  // copied by fork().
  std::optional<geom::ToolPose> cut_end_;
  const geom::ToolPart* cut_end_part_ = nullptr;
  CutBatch batch_;
  // Each tool's removed volume is the stock's volume when it started cutting less
  // its volume when the next one did (or now): the steps keep no volume deltas.
  int removal_tool_ = -1;
  bool removal_touched_ = false;  // removal_tool_ has changed the stock
  double removal_start_ = 0.0;    // mm^3

  Episodes episodes_;
  RunStats stats_;
  OverhangStats overhang_;
  Timing timing_;
  std::chrono::steady_clock::time_point started_;
  std::function<void(const gcode::SourcePos&, std::int64_t)> progress_;
  const std::atomic<bool>* cancel_ = nullptr;
  std::function<void(std::size_t)> contact_listener_;
};

}  // namespace mdhd::check

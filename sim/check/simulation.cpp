#include "sim/check/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "sim/check/contact_depth.h"
#include "sim/check/overhang_area.h"
#include "sim/geometry/pose_interpolation.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_fresh_region.h"
#include "sim/kinematics/joint_path.h"
#include "sim/kinematics/limits.h"
#include "sim/kinematics/motion_time.h"

namespace mdhd::check {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kBisections = 12;         // first contact within 1/4096 of a step
constexpr int kAnnounceBisections = 4;  // a listener hears it within 1/16 of a step

double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Adds the time spent in a scope to a counter, less what `nested` (another
// counter, timed inside the scope) gained meanwhile.
class ScopeTimer {
 public:
  explicit ScopeTimer(double& ms, const double* nested = nullptr)
      : ms_(ms), nested_(nested), nestedStart_(nested ? *nested : 0.0), start_(Clock::now()) {}
  ~ScopeTimer() { ms_ += msSince(start_) - (nested_ ? *nested_ - nestedStart_ : 0.0); }
  ScopeTimer(const ScopeTimer&) = delete;
  ScopeTimer& operator=(const ScopeTimer&) = delete;

 private:
  double& ms_;
  const double* nested_;
  double nestedStart_;
  Clock::time_point start_;
};

mdh::StockOptions stockOptions(const SimulationOptions& o, const kin::Machine& machine,
                               const std::vector<geom::Tool>& tools, const geom::Aabb& stock) {
  mdh::StockOptions s;
  s.brick_z = o.brick_z;
  if (o.brick_z == SimulationOptions::kBrickZAuto) {
    const bool rotary =
        std::any_of(machine.joints.begin(), machine.joints.end(),
                    [](const kin::Joint& j) { return j.type == kin::JointType::kRotary; });
    // Flutes as long as the stock is tall remove whole columns: no overhang can
    // arise. Shorter ones can leave one under a buried shank (a crash), and a cell
    // that unpacks or answers grid lines across it costs its height in levels.
    const double height = stock.hi.z - stock.lo.z;
    const bool throughFlutes = std::all_of(
        tools.begin(), tools.end(), [&](const geom::Tool& t) { return t.flute_length >= height; });
    s.brick_z = rotary ? -1 : throughFlutes ? 0 : SimulationOptions::kBrickZCap;
  }
  s.density = o.density;
  s.three_way = o.three_way;
  s.two_sided = o.two_sided;
  s.lazy_crossings = o.lazy_crossings;
  s.ruleset = o.ruleset;
  s.seed = o.seed;
  s.threads = o.threads;
  // Per-tool removal comes from the stock's volume at tool changes (closeToolRemoval),
  // so the steps need not integrate their volume change.
  s.step_volumes = false;
  return s;
}

ToolUse& toolUse(RunStats& stats, int tool) {
  for (ToolUse& u : stats.tools)
    if (u.tool == tool) return u;
  stats.tools.push_back({tool, 0.0, 0.0});
  return stats.tools.back();
}

// A material point is never deeper inside a part than the part's radius, so a part no
// wider than twice the contact tolerance can bury itself without a collision (a 0.15 mm
// cutter rapided 1 mm into stock at density 5 ran "clean"). With the default tolerance
// (h/2) that is also a cutter no wider than a grid spacing, which can pass between the
// grid lines without cutting.
std::string blindTo(const geom::Tool& tool, bool shank, double tolerance,
                    const SimulationOptions& options) {
  const auto tooThin = [&](const char* part, double diameter) {
    char text[360];
    std::snprintf(text, sizeof text,
                  "tool %d's %s (%g mm across) is no wider than twice the contact tolerance "
                  "(%g mm): none of its contacts could be told from grazing; give "
                  "options.density above %.3g points/mm (the default tolerance is half a grid "
                  "spacing) or a smaller options.contact_tolerance",
                  tool.number, part, diameter, tolerance,
                  std::max(options.density, 1.0 / diameter));
    return std::string(text);
  };
  if (tool.diameter <= 2.0 * tolerance) return tooThin("cutter", tool.diameter);
  if (shank && tool.shank_diameter <= 2.0 * tolerance) return tooThin("shank", tool.shank_diameter);
  return {};
}

}  // namespace

// One in-between step of one motion, with the sweeps of the tool's parts over it.
struct Simulation::Step {
  const gcode::Motion& m;
  const kin::JointPath& path;
  const ToolParts& parts;
  const StepPose& a;
  const StepPose& b;
  geom::SweptVolume cutter;
  std::optional<geom::SweptVolume> shank;
  std::optional<geom::SweptVolume> holder;
};

Simulation::Simulation(const kin::Kinematics& kin, const std::vector<geom::Tool>& tools,
                       const geom::Aabb& stock,
                       std::vector<std::unique_ptr<geom::LineSolid>> fixtures,
                       SimulationOptions options)
    : kin_(kin),
      fixtures_(std::make_shared<const std::vector<std::unique_ptr<geom::LineSolid>>>(
          std::move(fixtures))),
      options_(std::move(options)),
      batch_(options_.batch_steps,
             options_.chain_tolerance < 0.0 ? 0.5 * options_.tolerance : options_.chain_tolerance),
      started_(Clock::now()) {
  for (const geom::Tool& t : tools) {
    ToolParts p{t,
                geom::makeToolPart(t, geom::ToolPartKind::kCutter),
                geom::makeToolPart(t, geom::ToolPartKind::kShank),
                geom::makeToolPart(t, geom::ToolPartKind::kHolder),
                0.0,
                {},
                {},
                {}};
    for (const geom::ToolPart* part : {&p.cutter, &p.shank, &p.holder})
      if (!part->empty()) p.reach = std::max(p.reach, part->reach());
    for (auto [part, ball] :
         {std::pair{&p.shank, &p.shankBall}, std::pair{&p.holder, &p.holderBall}})
      if (!part->empty()) *ball = {part->centreHeight(), part->reach(part->centreHeight())};
    tools_.emplace(t.number, std::move(p));
  }
  stock_ = std::make_unique<mdh::Stock>(stock, stockOptions(options_, kin.machine(), tools, stock));
  contact_tolerance_ =
      options_.contact_tolerance >= 0.0 ? options_.contact_tolerance : 0.5 / options_.density;
  for (auto& [number, p] : tools_)
    p.blind = blindTo(p.tool, !p.shank.empty(), contact_tolerance_, options_);
  stats_.stock_volume_mm3 = stock_->volume();
  removal_start_ = stats_.stock_volume_mm3;
}

Simulation::Simulation(const Simulation& from, ForkTag)
    : kin_(from.kin_),
      tools_(from.tools_),
      stock_(from.stock_->clone()),
      fixtures_(from.fixtures_),
      options_(from.options_),
      contact_tolerance_(from.contact_tolerance_),
      current_tool_(from.current_tool_),
      batch_(from.options_.batch_steps),
      episodes_(from.episodes_),
      started_(Clock::now()) {
  stats_.stock_volume_mm3 = stock_->volume();
  removal_start_ = stats_.stock_volume_mm3;
}

std::string Simulation::stockProblem(const kin::Machine& machine,
                                     const std::vector<geom::Tool>& tools, const geom::Aabb& stock,
                                     const SimulationOptions& options) {
  return mdh::Stock::gridProblem(stock, stockOptions(options, machine, tools, stock));
}

Simulation::~Simulation() = default;

void Simulation::requireFlushed(const char* what) const {
  if (!batch_.empty())
    throw std::logic_error(std::string("Simulation::") + what +
                           " with cuts still batched: call flushCuts() first");
}

std::unique_ptr<Simulation> Simulation::fork() const {
  requireFlushed("fork");
  return std::unique_ptr<Simulation>(new Simulation(*this, ForkTag{}));
}

const Simulation::ToolParts* Simulation::partsFor(int tool) {
  const auto it = tools_.find(tool);
  if (it == tools_.end()) return nullptr;
  if (tool != current_tool_) {
    current_tool_ = tool;
    stock_->setToolRadius(it->second.tool.radius());
  }
  return &it->second;
}

void Simulation::checkCancel() const {
  if (cancel_ != nullptr && cancel_->load(std::memory_order_relaxed)) throw Cancelled();
}

void Simulation::motion(const gcode::Motion& m) {
  if (const std::string& blind = blindReason(m.tool); !blind.empty())
    throw gcode::GcodeError(m.pos, blind);
  if (m.spindle != gcode::SpindleState::kOff && !(m.spindle_rpm > 0.0)) {
    // M3/M4 at S0, or with no S ever given: the spindle stands still, and a cut is a cut
    // with the spindle off (it ran `clean` until session 23). A live machine's motions
    // (machineMotion) carry no speed and keep the state they report.
    gcode::Motion still = m;
    still.spindle = gcode::SpindleState::kOff;
    simulate(still, nullptr);
    return;
  }
  simulate(m, nullptr);
}

const std::string& Simulation::blindReason(int tool) const {
  static const std::string kNone;
  const auto it = tools_.find(tool);
  return it == tools_.end() ? kNone : it->second.blind;
}

void Simulation::machineMotion(const gcode::Motion& m, double seconds) {
  simulate(m, &seconds);
  flushCuts();  // a live stock is the machine's now
}

void Simulation::simulate(const gcode::Motion& m, const double* known_seconds) {
  checkCancel();
  switch (m.type) {
    case gcode::MotionType::kRapid:
      ++stats_.moves.rapid;
      break;
    case gcode::MotionType::kFeed:
      ++stats_.moves.feed;
      break;
    case gcode::MotionType::kArc:
      ++stats_.moves.arc;
      break;
  }
  const ToolParts* parts = partsFor(m.tool);
  try {
    const kin::JointPath path(kin_, m, parts != nullptr ? parts->tool.length : 0.0);
    checkLimits(m, path);
    const std::vector<StepPose> poses =
        stepPoses(path, options_.steps, options_.tolerance, parts != nullptr ? parts->reach : 0.0);
    if (!material_before_.empty()) {
      material_before_.clear();
      material_before_intervals_ = 0;
    }
    bool removed = false;
    for (std::size_t i = 1; i < poses.size(); ++i) {
      const glm::dvec3 d = poses[i].pose.tip - poses[i - 1].pose.tip;
      const double chord = glm::length(d);
      // Beyond ~1e154 mm the squares overflow: the path was infinite, reported as 0.
      stats_.path_length += std::isfinite(chord) ? chord : std::hypot(d.x, d.y, d.z);
      runStep(m, path, parts, poses[i - 1], poses[i], removed);
    }
    const double seconds =
        known_seconds != nullptr ? *known_seconds : kin::motionSeconds(m, kin_, path.toolLength());
    stats_.cycle_time_s += seconds;
    if (removed && m.type != gcode::MotionType::kRapid && parts != nullptr) {
      toolUse(stats_, m.tool).cutting_time_s += seconds;
    }
  } catch (const kin::KinematicsError& e) {
    throw gcode::GcodeError(m.pos, std::string("cannot simulate this move: ") + e.what());
  } catch (const kin::MotionTimeError& e) {
    throw gcode::GcodeError(m.pos, std::string("cannot time this move: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw gcode::GcodeError(m.pos, std::string("cannot simulate this move: ") + e.what());
  }
  if (progress_) progress_(m.pos, stats_.moves.total());
}

void Simulation::event(const gcode::Event& e) {
  stats_.cycle_time_s += kin::eventSeconds(e);
}

void Simulation::checkLimits(const gcode::Motion& m, const kin::JointPath& path) {
  // Every joint beyond its range is its own episode: until session 22 only the one that
  // left first was looked at, so a second joint's overtravel in the same move was
  // missed or reported at a later line. Each side of a joint is its own episode too.
  for (const kin::LimitViolation& v : kin::checkLimitsAll(path)) {
    const EpisodeKey key{CollisionType::kAxisLimit, ToolPartName::kNone, -1, v.joint, 0, v.side};
    episodes_.touch(key, v.excess, m.pos.line, [&] {
      Collision c;
      c.type = CollisionType::kAxisLimit;
      c.file = m.pos.file;
      c.line = m.pos.line;
      if (m.block_text != nullptr) c.block = *m.block_text;
      c.tool = m.tool;
      c.joints = path.at(v.first_s);
      c.path_s = v.first_s;
      c.position = toolPoseAt(path, c.joints).tip;
      c.axis = kin_.machine().joints[static_cast<std::size_t>(v.joint)].name;
      return c;
    });
    // Back inside (or beyond the other side) at the move's end: a later overtravel of
    // this side is a new episode.
    if (!v.outside_at_end) episodes_.close(key);
  }
  episodes_.endStep(true);
}

geom::SweptVolume Simulation::sweep(const Step& step, const geom::ToolPart& part, double f) const {
  if (f >= 1.0) return sweep(step.a.pose, step.b.pose, part);
  // The pose on the path, where entry() reports the contact: a turn's chord pose lies
  // inside the arc (a table turn's first contact came up to a step's chord early).
  const double s = step.a.s + f * (step.b.s - step.a.s);
  return sweep(step.a.pose, toolPoseAt(step.path, step.path.at(s)), part);
}

geom::SweptVolume Simulation::sweep(const geom::ToolPose& a, const geom::ToolPose& end,
                                    const geom::ToolPart& part) const {
  const double tol = part.kind == geom::ToolPartKind::kCutter
                         ? options_.tolerance
                         : std::max(options_.tolerance, contact_tolerance_);
  // Each segment of a turning move holds its middle pose's axis: one translation
  // fewer per step for the same errorBound() (the end poses are then within it too,
  // and consecutive steps overlap there).
  return geom::SweptVolume::between(part, a, end, options_.steps > 0 ? 1 : 0, tol,
                                    geom::SweepEnds::kMidpoints);
}

bool Simulation::mayTouchStock(const PartBall& ball, const geom::ToolPose& a,
                               const geom::ToolPose& b) const {
  if (ball.radius < 0.0) return false;
  if (!fixtures_->empty() || a.axis != b.axis) return true;
  // Translated, the part stays in the capsule of its ball: compare boxes.
  const mdh::GridSpec& g = stock_->grid();
  // The sweep may stand out of the part by its tolerance; a grid spacing more for luck.
  const double margin =
      ball.radius + std::max(options_.tolerance, contact_tolerance_) + contact_tolerance_ + g.h;
  for (int i = 0; i < 3; ++i) {
    const double ca = a.tip[i] + ball.height * a.axis[i], cb = b.tip[i] + ball.height * b.axis[i];
    const double lo = g.origin[i], hi = g.origin[i] + g.cubes[i] * g.h;
    if (std::min(ca, cb) - margin > hi || std::max(ca, cb) + margin < lo) return false;
  }
  return true;
}

Collision Simulation::entry(const Step& step, CollisionType type, double f) const {
  Collision c;
  c.type = type;
  c.file = step.m.pos.file;
  c.line = step.m.pos.line;
  if (step.m.block_text != nullptr) c.block = *step.m.block_text;
  c.tool = step.m.tool;
  c.path_s = f >= 1.0 ? step.b.s : step.a.s + f * (step.b.s - step.a.s);
  c.joints = f >= 1.0 ? step.b.q : step.path.at(c.path_s);
  c.position = toolPoseAt(step.path, c.joints).tip;  // on the path, not the step's chord
  return c;
}

// The first-contact bisection so far: carried on, it ends where it would in one go.
struct Simulation::Bracket {
  double lo = 0.0, hi = 1.0;
  int done = -1;  // bisections made; -1: the step's start not tried yet
};

Penetration Simulation::contact(const Step& step, const EpisodeKey& key, const geom::ToolPart& part,
                                const Touches& touches,
                                const std::function<Penetration(double enough)>& measure) {
  Bracket bracket;
  const auto start = [&](int bisections) {
    Collision c = entry(step, key.type, firstContact(step, part, touches, bracket, bisections));
    c.part = key.part;
    c.fixture = key.fixture;
    return c;
  };
  const int line = step.m.pos.line;
  if (contact_listener_ && !episodes_.isOpen(key)) {
    // Announce a new contact as soon as a sample proves it and a coarse bisection
    // places it; measure and place it exactly after.
    const Penetration first = measure(contact_tolerance_);
    if (!(first.depth > contact_tolerance_)) return first;
    episodes_.touch(key, first.depth, line, [&] { return start(kAnnounceBisections); });
    const std::size_t index = episodes_.collisions().size() - 1;
    contact_listener_(index);
    const Collision exact = start(kBisections);
    Collision& c = episodes_.collisions()[index];
    c.path_s = exact.path_s;
    c.joints = exact.joints;
    c.position = exact.position;
  }
  const Penetration p = measure(deepEnough(part));
  if (p.depth > contact_tolerance_)
    episodes_.touch(key, p.depth, line, [&] { return start(kBisections); });
  return p;
}

double Simulation::firstContact(const Step& step, const geom::ToolPart& part,
                                const Touches& touches, Bracket& bracket, int bisections) const {
  if (bracket.done < 0) {
    bracket.done = 0;
    if (touches(geom::SweptVolume::at(part, step.a.pose))) {
      bracket.hi = 0.0;
      bracket.done = kBisections;
    }
  }
  for (; bracket.done < bisections; ++bracket.done) {
    const double mid = 0.5 * (bracket.lo + bracket.hi);
    (touches(sweep(step, part, mid)) ? bracket.hi : bracket.lo) = mid;
  }
  return bracket.hi;
}

void Simulation::runStep(const gcode::Motion& m, const kin::JointPath& path, const ToolParts* parts,
                         const StepPose& a, const StepPose& b, bool& removed) {
  checkCancel();
  ++stats_.steps;
  if (parts != nullptr) {
    Step step{m, path, *parts, a, b, sweep(a.pose, b.pose, parts->cutter), {}, {}};
    // A shank or holder far above the stock needs no sweep: it cannot touch.
    if (mayTouchStock(parts->shankBall, a.pose, b.pose))
      step.shank = sweep(step, parts->shank, 1.0);
    if (mayTouchStock(parts->holderBall, a.pose, b.pose))
      step.holder = sweep(step, parts->holder, 1.0);
    cutterStep(step, removed);
    stockContacts(step);
    if (!fixtures_->empty()) fixtureContacts(step);
  }
  episodes_.endStep(false);
}

namespace {

LineGrid stockLines(const mdh::Stock& stock) {
  const mdh::GridSpec& g = stock.grid();
  return {g.origin.x, g.origin.y, g.h, 0, g.cubes[0], 0, g.cubes[1]};
}

}  // namespace

void Simulation::cutterStep(const Step& step, bool& removed) {
  const gcode::Motion& m = step.m;
  const geom::ToolPose& a = step.a.pose;
  const bool rapid = m.type == gcode::MotionType::kRapid;
  const bool spindleOff = m.spindle == gcode::SpindleState::kOff;
  const bool translation = a.axis == step.b.pose.axis;
  // Where the last cut left this cutter: the fresh region skips what it removed (a
  // turn from its held pose into this step's first one included).
  std::optional<geom::FreshRegion> fresh;
  if (options_.fresh_regions && cut_end_ && cut_end_part_ == &step.parts.cutter) {
    if (translation && cut_end_->tip == a.tip && cut_end_->axis == a.axis)
      fresh = geom::freshRegion(step.parts.cutter, a, step.b.pose);
    else
      fresh = geom::freshRegion(step.parts.cutter, *cut_end_, step.cutter.translations());
  }
  // A step joins the batch when it continues the last cut (which a pending batch
  // made: cut_end_ is its end) with the axis held; anything else is cut after it.
  const bool batched = fresh && translation && !rapid && !spindleOff;
  if (!batched) flushCuts();
  if (rapid || spindleOff) {
    // The removal itself is the collision: measure it before the material is gone, and
    // against the material as the motion met it: a turning rapid's later steps find
    // only the slivers its earlier steps left (a cutter swung whole into the stock
    // measured a quarter of its radius at 1/3 degree a step).
    ScopeTimer timer(timing_.probe_ms);
    if (stock_->probe(step.cutter, contact_tolerance_).touched) {
      const auto material = [this](int ix, int iy, double, double,
                                   std::vector<geom::Interval>& out) {
        const auto it = material_before_.find(static_cast<std::uint32_t>(ix) |
                                              std::uint64_t{static_cast<std::uint32_t>(iy)} << 32);
        if (it != material_before_.end())
          out = it->second;
        else
          stock_->solidIntervals(2, ix, iy, out);
      };
      const geom::Aabb all{glm::dvec3(-INFINITY), glm::dvec3(INFINITY)};
      const EpisodeKey key{rapid ? CollisionType::kRapidIntoStock : CollisionType::kSpindleOffCut,
                           ToolPartName::kCutter, -1, -1, m.tool};
      if (measureCanWait(key, step, step.parts.cutter)) {
        episodes_.touch(key, 0.0, m.pos.line, [] { return Collision{}; });
      } else {
        const auto measure = [&](double enough) {
          return penetration(step.cutter, step.parts.cutter, all, stockLines(*stock_), material,
                             true, enough);
        };
        const Penetration p = contact(
            step, key, step.parts.cutter,
            [&](const geom::SweptVolume& s) {
              return stock_->probe(s, contact_tolerance_).touched;
            },
            measure);
        if (p.depth > contact_tolerance_) episodes_.measured(key);
      }
      keepMaterialBefore(step.cutter);
    }
  }
  glm::dvec3 dir = a.axis + step.b.pose.axis;
  dir = glm::dot(dir, dir) > 1e-12 ? glm::normalize(dir) : step.b.pose.axis;
  if (m.tool != removal_tool_) closeToolRemoval(m.tool);
  // The pose the cut leaves the cutter held at: a turning step's last translation
  // holds an in-between axis (SweepEnds::kMidpoints).
  const auto& held = step.cutter.translations();
  if (translation)
    cut_end_ = step.b.pose;
  else if (!held.empty())
    cut_end_ = geom::ToolPose{held.back().to, held.back().axis};
  else
    cut_end_.reset();
  cut_end_part_ = &step.parts.cutter;
  if (batched) {
    {
      // Whether this step removes material is asked before its cut is made (the
      // batch's cuts come later), of the stock less the steps batched before it;
      // not at all once an earlier step of the motion has.
      ScopeTimer timer(timing_.cut_ms);
      if (batch_.add(*stock_, step.parts.cutter, a, step.b.pose, step.cutter, std::move(*fresh),
                     dir, m.pos.line, m.type == gcode::MotionType::kFeed, !removed))
        removed = true;
    }
    if (batch_.full()) flushCuts();
    return;
  }
  ScopeTimer timer(timing_.cut_ms);
  // Shared, so that z maps may keep the sweep for their crossings (mdh::Stock::cut);
  // `removed` then says whether it surely removed material (a z map's crossings that
  // alone moved do not count, lazy or not).
  const mdh::CutResult r = stock_->cut(std::make_shared<const geom::SweptVolume>(step.cutter), dir,
                                       fresh ? &*fresh : nullptr);
  if (r.removed) removed = true;
  noteCut(r, m.pos.line);
}

void Simulation::noteCut(const mdh::CutResult& r, int line) {
  if (r.touched) removal_touched_ = true;
  if (r.overhang_events > 0) {
    overhang_.events += r.overhang_events;
    if (!overhang_.first_line) overhang_.first_line = line;
  }
}

void Simulation::flushCuts() {
  if (batch_.empty()) return;
  ScopeTimer timer(timing_.cut_ms);
  batch_.flush(*stock_, [this](int line, const mdh::CutResult& r) { noteCut(r, line); });
}

double Simulation::deepEnough(const geom::ToolPart& part) const {
  // Nothing lies deeper in a part than its widest radius, and the depth is sampled on
  // grid lines: a sample within a quarter spacing of that radius ends the measure (a
  // whole cutter buried by a turning rapid took 0.2 s a step to confirm).
  return part.maxRadius() - 0.25 * stock_->grid().h;
}

bool Simulation::measureCanWait(const EpisodeKey& key, const Step& step,
                                const geom::ToolPart& part) {
  if (!episodes_.isOpen(key)) return false;
  // Depth grows no faster than the part moves (the material only shrinks): within a
  // grid spacing of travel since the last measure it cannot have grown by more. Not the
  // overlap along z lines, as once: a shank pushed sideways keeps its height in the
  // material while it goes deeper (moves of 0.04 mm kept a 2.3 mm contact at 0.11).
  episodes_.addTravel(key, chordTravel(step, part));
  return episodes_.travelSinceMeasured(key) + options_.tolerance <= stock_->grid().h ||
         episodes_.depth(key) >= deepEnough(part);
}

double Simulation::chordTravel(const Step& step, const geom::ToolPart& part) {
  const geom::ToolPose& a = step.a.pose;
  const geom::ToolPose& b = step.b.pose;
  const double turn = std::acos(std::clamp(glm::dot(a.axis, b.axis), -1.0, 1.0));
  return glm::length(b.tip - a.tip) + turn * part.reach();
}

void Simulation::keepMaterialBefore(const geom::SweptVolume& sweep) {
  // A bound on what one motion may keep (16 M intervals, a few hundred MB): beyond it,
  // lines are measured as the stock holds them now (shallower, never deeper).
  constexpr std::size_t kMaxIntervals = std::size_t{1} << 24;
  const mdh::GridSpec& g = stock_->grid();
  const geom::Aabb b = sweep.bounds();
  const auto lo = [&](double v, double o, int n) {
    return std::clamp(static_cast<int>(std::floor((v - o) / g.h)), 0, n);
  };
  const auto hi = [&](double v, double o, int n) {
    return std::clamp(static_cast<int>(std::ceil((v - o) / g.h)), 0, n);
  };
  const int ix0 = lo(b.lo.x, g.origin.x, g.cubes[0]), ix1 = hi(b.hi.x, g.origin.x, g.cubes[0]);
  const int iy0 = lo(b.lo.y, g.origin.y, g.cubes[1]), iy1 = hi(b.hi.y, g.origin.y, g.cubes[1]);
  for (int iy = iy0; iy <= iy1; ++iy)
    for (int ix = ix0; ix <= ix1; ++ix) {
      if (material_before_intervals_ >= kMaxIntervals) return;
      const auto [it, fresh] = material_before_.try_emplace(
          static_cast<std::uint32_t>(ix) | std::uint64_t{static_cast<std::uint32_t>(iy)} << 32);
      if (!fresh) continue;
      stock_->solidIntervals(2, ix, iy, it->second);
      material_before_intervals_ += std::max<std::size_t>(1, it->second.size());
    }
}

void Simulation::stockContacts(const Step& step) {
  ScopeTimer timer(timing_.probe_ms, &timing_.cut_ms);  // batched cuts made here are cut time
  const auto material = [this](int ix, int iy, double, double, std::vector<geom::Interval>& out) {
    stock_->solidIntervals(2, ix, iy, out);
  };
  const geom::Aabb all{glm::dvec3(-INFINITY), glm::dvec3(INFINITY)};
  const struct {
    const std::optional<geom::SweptVolume>& sweep;
    const geom::ToolPart& part;
    CollisionType type;
    ToolPartName name;
  } checks[] = {
      {step.shank, step.parts.shank, CollisionType::kShankContact, ToolPartName::kShank},
      {step.holder, step.parts.holder, CollisionType::kHolderContact, ToolPartName::kHolder},
  };
  for (const auto& check : checks) {
    if (!check.sweep) continue;
    mdh::Overlap overlap = stock_->probe(*check.sweep, contact_tolerance_);
    if (!overlap.touched) continue;
    if (!batch_.empty()) {
      // The stock still holds what the batched steps remove: an overlap may be theirs.
      flushCuts();
      overlap = stock_->probe(*check.sweep, contact_tolerance_);
      if (!overlap.touched) continue;
    }
    const EpisodeKey key{check.type, check.name, -1, -1, step.m.tool};
    if (measureCanWait(key, step, check.part)) {
      episodes_.touch(key, 0.0, step.m.pos.line, [] { return Collision{}; });
      continue;
    }
    const auto measure = [&](double enough) {
      return penetration(*check.sweep, check.part, all, stockLines(*stock_), material, true,
                         enough);
    };
    const Penetration p = contact(
        step, key, check.part,
        [&](const geom::SweptVolume& s) { return stock_->probe(s, contact_tolerance_).touched; },
        measure);
    if (p.depth > contact_tolerance_) episodes_.measured(key);
  }
}

void Simulation::fixtureContacts(const Step& step) {
  ScopeTimer timer(timing_.probe_ms);
  const mdh::GridSpec& g = stock_->grid();
  const LineGrid lines{g.origin.x, g.origin.y, g.h, -(1 << 28), 1 << 28, -(1 << 28), 1 << 28};
  const struct {
    const geom::SweptVolume* sweep;
    const geom::ToolPart& part;
    ToolPartName name;
  } parts[] = {
      {&step.cutter, step.parts.cutter, ToolPartName::kCutter},
      {step.shank ? &*step.shank : nullptr, step.parts.shank, ToolPartName::kShank},
      {step.holder ? &*step.holder : nullptr, step.parts.holder, ToolPartName::kHolder},
  };
  for (std::size_t i = 0; i < fixtures_->size(); ++i) {
    const geom::LineSolid& fixture = *(*fixtures_)[i];
    const geom::Aabb fb = fixture.bounds();
    const auto material = [&fixture](int, int, double x, double y,
                                     std::vector<geom::Interval>& out) {
      fixture.lineIntervals(2, x, y, out);
    };
    for (const auto& part : parts) {
      if (part.sweep == nullptr || part.part.empty() ||
          isEmpty(intersect(part.sweep->bounds(), fb)))
        continue;
      const EpisodeKey key{CollisionType::kFixtureContact, part.name, static_cast<int>(i), -1,
                           step.m.tool};
      // As for the stock, while the part still overlaps the fixture.
      if (measureCanWait(key, step, part.part) &&
          penetration(*part.sweep, part.part, fb, lines, material, false).max_overlap >
              contact_tolerance_) {
        episodes_.touch(key, 0.0, step.m.pos.line, [] { return Collision{}; });
        continue;
      }
      const auto measure = [&](double enough) {
        return penetration(*part.sweep, part.part, fb, lines, material, true, enough);
      };
      // Only whether it touches: the first sample over the tolerance settles it.
      const Penetration p = contact(
          step, key, part.part,
          [&](const geom::SweptVolume& s) {
            return penetration(s, part.part, fb, lines, material, true, contact_tolerance_).depth >
                   contact_tolerance_;
          },
          measure);
      if (p.depth > contact_tolerance_) episodes_.measured(key);
    }
  }
}

void Simulation::closeToolRemoval(int next) {
  if (removal_touched_) {
    stock_->settle();  // on the stock's threads, before volume() reads the maps
    const double v = stock_->volume();
    // A lazy batch counts as touched wherever it reaches a cut map (mdh::Stock::cutIfFast):
    // a tool is credited only with what the volume says it removed.
    if (removal_start_ - v > 0.0)
      toolUse(stats_, removal_tool_).removed_volume_mm3 += removal_start_ - v;
    removal_start_ = v;
  }
  removal_tool_ = next;
  removal_touched_ = false;
}

Report Simulation::snapshot(std::int64_t blocks) const {
  requireFlushed("snapshot");
  Report report;
  RunStats stats = stats_;
  stats.blocks = blocks;
  stats.final_volume_mm3 = stock_->volume();
  stats.removed_volume_mm3 = stats.stock_volume_mm3 - stats.final_volume_mm3;
  if (removal_touched_ && removal_start_ - stats.final_volume_mm3 > 0.0)
    toolUse(stats, removal_tool_).removed_volume_mm3 += removal_start_ - stats.final_volume_mm3;
  report.mdh = stock_->stats();
  OverhangStats overhang = overhang_;
  const auto& d = report.mdh.directions;
  overhang.cells_not_plus_z = d[0] + d[1] + d[2] + d[3] + d[5];
  overhang.area_mm2 = overhangArea(*stock_, stock_->threads());
  report.collisions = episodes_.collisions();
  report.status = report.collisions.empty() ? Status::kClean : Status::kCollisions;
  report.stats = std::move(stats);
  report.overhang = overhang;
  report.timing = timing_;
  report.timing.total_ms = msSince(started_);
  report.grid_spacing = stock_->grid().h;
  return report;
}

Report Simulation::finish(std::int64_t blocks) {
  flushCuts();
  const Clock::time_point t0 = Clock::now();
  stock_->settle();  // the crossings cuts left pending, on the stock's threads
  Report report = snapshot(blocks);
  timing_.finish_ms += msSince(t0);
  timing_.total_ms = msSince(started_);
  report.timing = timing_;
  return report;
}

}  // namespace mdhd::check

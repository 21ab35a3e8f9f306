#pragma once
// The live half of a shadow without its threads: polled samples become motions
// (straight in joint space from one poll to the next), each checked and cut by a
// check::Simulation exactly as a program's motion, and the collision episodes
// they open come back as alarms. Samples on one straight joint-space line are
// cut as one motion (the same sweep, fewer steps): that is how the carving
// catches up when polls arrive faster than it cuts.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "daemon/shadow_program.h"
#include "protocol/job.h"
#include "sim/check/simulation.h"

namespace mdhd::shadow {

using SteadyClock = std::chrono::steady_clock;

// One poll, decoded.
struct PollSample {
  SteadyClock::time_point t{};
  gcode::AxisValues joints{};
  std::optional<int> tool;
  std::optional<bool> spindle_on;
  std::optional<std::int64_t> line;
  // First sample after the start or after a stale period: where the machine went
  // meanwhile is unknown, so no motion is cut into this sample (none is invented).
  bool resync = false;
};

struct CarveResult {
  std::vector<check::Collision> alarms;  // episodes that began in this batch
  std::int64_t motions = 0;              // simulated motions
  std::int64_t merged = 0;               // samples folded into a longer straight motion
  std::vector<std::string> errors;       // motions the engine could not simulate
};

// Joint-space distance within which a sample counts as on a straight line.
inline constexpr double kStraightTolerance = 1e-3;  // mm or degrees

class ShadowCarver {
 public:
  // `job`, `kin` and `track` (null without a program) must outlive the carver.
  // Throws std::invalid_argument for a stock or tool the engine cannot use.
  ShadowCarver(const protocol::Job& job, const kin::Kinematics& kin, const ProgramTrack* track);

  // Called from inside carve() the moment a contact opens an episode, before the
  // motion is finished and its depth measured (the collision holds a first bound):
  // to alarm without waiting. The episode is still listed in CarveResult::alarms.
  void setAlarmListener(std::function<void(const check::Collision&, std::size_t episode)> listener);

  // Cuts the motions up to each sample of the batch, in order.
  CarveResult carve(std::span<const PollSample> batch);

  const check::Simulation& simulation() const { return *sim_; }
  // The program motion the machine was last placed on (with a program and a line).
  std::optional<std::size_t> cursor() const { return cursor_; }
  const std::optional<PollSample>& last() const { return last_; }
  // The tool a sample stands for: its register, else the program's, else the
  // job's only tool, else 0 (none: nothing is cut).
  int toolOf(const PollSample& s) const;

 private:
  struct Kind {
    gcode::MotionType type = gcode::MotionType::kFeed;
    int tool = 0;
    gcode::SpindleState spindle = gcode::SpindleState::kClockwise;
    std::int64_t line = 0;
    bool operator==(const Kind&) const = default;
  };
  Kind kindOf(const PollSample& s);
  void cut(const PollSample& from, const PollSample& to, const Kind& kind, CarveResult& out);

  const protocol::Job& job_;
  const ProgramTrack* track_;
  std::unique_ptr<check::Simulation> sim_;
  std::optional<PollSample> last_;
  Kind last_kind_;
  std::optional<std::size_t> cursor_;
  std::set<int> blind_said_;  // thin tools already reported (Simulation::blindReason)
  std::size_t alarms_seen_ = 0;
};

}  // namespace mdhd::shadow

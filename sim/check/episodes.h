#pragma once
// Collision episodes: a contact of one kind (type, tool part, fixture, joint, tool)
// starts at the first step that touches and ends at the first step that does
// not; the report holds one entry per episode with its first place and its
// deepest penetration.
#include <functional>
#include <map>
#include <tuple>
#include <vector>

#include "sim/check/report.h"

namespace mdhd::check {

struct EpisodeKey {
  CollisionType type = CollisionType::kRapidIntoStock;
  ToolPartName part = ToolPartName::kNone;
  int fixture = -1;
  int joint = -1;
  // The tool of a contact: a tool change ends every contact of the tool before it (a
  // rapid or holder contact of tool 2 right after one of tool 1 was reported as tool
  // 1's, at its line, until session 23). Axis limits keep 0: a joint's overtravel is
  // the machine's, whichever tool is in the spindle.
  int tool = 0;
  // Axis limits: the side beyond which the joint is (+1 max, -1 min; 0 for contacts).
  // A move from below a joint's min to beyond its max ends the min episode and opens a
  // max one: until session 23 both were one episode, reported at the min side's line
  // with the max side's depth, and the max overtravel was never named.
  int side = 0;
  auto operator<=>(const EpisodeKey&) const = default;
};

class Episodes {
 public:
  // A step touched: continues the open episode of `key` (deepening it) or, when none
  // is open, opens one with the entry `start()` builds (called only then).
  void touch(const EpisodeKey& key, double depth, int line,
             const std::function<Collision()>& start);
  // Ends the open episode of `key` now (if any): the next touch opens a new one.
  void close(const EpisodeKey& key) { open_.erase(key); }
  // Whether an episode of `key` is open (touched by the previous step).
  bool isOpen(const EpisodeKey& key) const { return open_.count(key) != 0; }
  // How far (mm) any point of the part may have moved since the open episode of `key`
  // was last measured, or -1 when none is open. Depth grows no faster than the part
  // moves (the material only shrinks), so until it passes the depth's resolution the
  // episode need not be measured again.
  double travelSinceMeasured(const EpisodeKey& key) const;
  void addTravel(const EpisodeKey& key, double mm);
  void measured(const EpisodeKey& key);
  // The depth of the open episode of `key` so far (-1 when none is open).
  double depth(const EpisodeKey& key) const;
  // Ends a step: episodes of `scope` not touched since the last endStep are closed.
  // Scopes keep per-step contacts apart from per-motion ones (axis limits).
  void endStep(bool motionScope);

  std::vector<Collision>& collisions() { return collisions_; }
  const std::vector<Collision>& collisions() const { return collisions_; }

 private:
  struct Open {
    std::size_t index = 0;
    bool touched = false;
    double travel = 0.0;  // mm, since the last measurement
  };
  std::map<EpisodeKey, Open> open_;
  std::vector<Collision> collisions_;
};

}  // namespace mdhd::check

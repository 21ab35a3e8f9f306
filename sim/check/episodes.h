#pragma once
// Collision episodes: a contact of one kind (type, tool part, fixture, joint)
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
  auto operator<=>(const EpisodeKey&) const = default;
};

class Episodes {
 public:
  // A step touched: continues the open episode of `key` (deepening it) or, when none
  // is open, opens one with the entry `start()` builds (called only then).
  void touch(const EpisodeKey& key, double depth, int line,
             const std::function<Collision()>& start);
  // Whether an episode of `key` is open (touched by the previous step).
  bool isOpen(const EpisodeKey& key) const { return open_.count(key) != 0; }
  // The longest overlap (mm along a grid line) noted for the open episode of `key`,
  // or -1 when none is open: a step that overlaps no more need not be measured again.
  double overlapSeen(const EpisodeKey& key) const;
  void noteOverlap(const EpisodeKey& key, double overlap);
  // Ends a step: episodes of `scope` not touched since the last endStep are closed.
  // Scopes keep per-step contacts apart from per-motion ones (axis limits).
  void endStep(bool motionScope);

  std::vector<Collision>& collisions() { return collisions_; }
  const std::vector<Collision>& collisions() const { return collisions_; }

 private:
  struct Open {
    std::size_t index = 0;
    bool touched = false;
    double overlap = 0.0;
  };
  std::map<EpisodeKey, Open> open_;
  std::vector<Collision> collisions_;
};

}  // namespace mdhd::check

#include "sim/check/episodes.h"

#include <algorithm>

namespace mdhd::check {

void Episodes::touch(const EpisodeKey& key, double depth, int line,
                     const std::function<Collision()>& start) {
  auto it = open_.find(key);
  if (it == open_.end()) {
    Collision c = start();
    c.depth = std::max(c.depth, depth);
    c.last_line = line;
    collisions_.push_back(std::move(c));
    open_.emplace(key, Open{collisions_.size() - 1, true});
    return;
  }
  Collision& c = collisions_[it->second.index];
  c.depth = std::max(c.depth, depth);
  c.last_line = line;
  it->second.touched = true;
}

double Episodes::travelSinceMeasured(const EpisodeKey& key) const {
  const auto it = open_.find(key);
  return it == open_.end() ? -1.0 : it->second.travel;
}

void Episodes::addTravel(const EpisodeKey& key, double mm) {
  if (const auto it = open_.find(key); it != open_.end()) it->second.travel += mm;
}

void Episodes::measured(const EpisodeKey& key) {
  if (const auto it = open_.find(key); it != open_.end()) it->second.travel = 0.0;
}

double Episodes::depth(const EpisodeKey& key) const {
  const auto it = open_.find(key);
  return it == open_.end() ? -1.0 : collisions_[it->second.index].depth;
}

void Episodes::endStep(bool motionScope) {
  for (auto it = open_.begin(); it != open_.end();) {
    const bool perMotion = it->first.type == CollisionType::kAxisLimit;
    if (perMotion != motionScope) {
      ++it;
      continue;
    }
    if (!it->second.touched) {
      it = open_.erase(it);
    } else {
      it->second.touched = false;
      ++it;
    }
  }
}

}  // namespace mdhd::check

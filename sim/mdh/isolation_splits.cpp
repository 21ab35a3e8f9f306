#include "sim/mdh/isolation_splits.h"

#include <algorithm>

#include "sim/mdh/region_bounds.h"

namespace mdhd::mdh {

namespace {

struct Projection {
  int lo, hi;
};

void addPlanes(int axis, int lo, int hi, SplitType type, bool complete, const GridBox& cell,
               std::vector<SplitCandidate>& out) {
  lo = std::max(lo, cell.lo[axis] + 1);
  hi = std::min(hi, cell.hi[axis] - 1);
  if (lo > hi) return;
  out.push_back({axis, lo, hi, type, complete, false});
}

// Planes along `axis` that separate u from the nearest conflict on each side:
// a separating interval gives complete splits, an overlap partial ones at the
// overlapped endpoints.
void isolate(int axis, Projection u, const std::vector<Projection>& conflicts, SplitType type,
             const GridBox& cell, std::vector<SplitCandidate>& out) {
  const Projection* left = nullptr;
  const Projection* right = nullptr;
  for (const Projection& c : conflicts) {
    if (c.lo + c.hi < u.lo + u.hi) {
      if (!left || c.hi > left->hi) left = &c;
    } else if (!right || c.lo < right->lo) {
      right = &c;
    }
  }
  // Children share the split plane's pixels, so a plane must lie strictly
  // between the two projections to separate them.
  if (left) {
    if (left->hi + 1 <= u.lo - 1) {
      addPlanes(axis, left->hi + 1, u.lo - 1, type, true, cell, out);
    } else {
      addPlanes(axis, u.lo, u.lo, type, false, cell, out);
      if (left->hi >= u.lo && left->hi <= u.hi)
        addPlanes(axis, left->hi, left->hi, type, false, cell, out);
    }
  }
  if (right) {
    if (u.hi + 1 <= right->lo - 1) {
      addPlanes(axis, u.hi + 1, right->lo - 1, type, true, cell, out);
    } else {
      addPlanes(axis, u.hi, u.hi, type, false, cell, out);
      if (right->lo >= u.lo && right->lo <= u.hi)
        addPlanes(axis, right->lo, right->lo, type, false, cell, out);
    }
  }
}

}  // namespace

void isolationSplits(const GoodBadMap& map, int oldAxis, const GridBox& cell,
                     std::vector<SplitCandidate>& out) {
  SplitType type;
  if (map.hasBad) {
    if (map.axis == oldAxis) return;  // the old axis's bad regions are the direct splits' job
    type = SplitType::kIndirect;
  } else if (map.hasPositive && map.hasNegative) {
    type = SplitType::kSignConflict;
  } else {
    return;
  }
  for (Pixel sign : {Pixel::kPositive, Pixel::kNegative}) {
    const auto regions =
        regionBounds(map, [&](std::size_t i) { return map.type[i] == sign && map.unresolved[i]; });
    if (regions.empty()) continue;
    const Pixel other = sign == Pixel::kPositive ? Pixel::kNegative : Pixel::kPositive;
    const Pixel conflictType = type == SplitType::kIndirect ? Pixel::kBad : other;
    const auto conflicts =
        regionBounds(map, [&](std::size_t i) { return map.type[i] == conflictType; });
    if (conflicts.empty()) continue;
    for (const PixelRect& u : regions) {
      std::vector<Projection> cp, cq;
      for (const PixelRect& c : conflicts) {
        cp.push_back({c.p0, c.p1});
        cq.push_back({c.q0, c.q1});
      }
      isolate(map.p, {u.p0, u.p1}, cp, type, cell, out);
      isolate(map.q, {u.q0, u.q1}, cq, type, cell, out);
    }
  }
}

}  // namespace mdhd::mdh

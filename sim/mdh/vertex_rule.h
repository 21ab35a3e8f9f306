#pragma once
// Which vertices a cut removes: one rule for every cell.
//
// Cells share the vertices of their common boundaries (and an inner node's
// split plane), and each cell holding such a vertex decides its state on its
// own. Deciding it along the cell's own direction would let neighbours of
// different directions disagree: a tool face through the vertex (within the
// cache's snapping) is "on" it along one line and "inside" along another
// (a line lying in the face). So every cell decides every vertex by the same
// test on the same tool intervals: removed iff it was solid and lies strictly
// inside the tool along the z line through it (the reference model's test).
// A z map's own lines are those z lines; x and y maps place only their
// crossings with their own lines (edgeCrossingAfterCut).
#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "sim/mdh/grid.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/line_segments.h"

namespace mdhd::mdh {

// zLine: the tool's intervals along the z line through the vertex.
inline bool toolRemovesVertex(std::span<const Span> zLine, int z) {
  return strictlyInside(zLine, z);
}

inline bool toolRemovesVertex(const IntervalCache& cache, const std::array<int, 3>& p) {
  return toolRemovesVertex(cache.line(2, p[0], p[1]), p[2]);
}

// Whether the rule removes any vertex of a solid box (a solid cell's probe).
inline bool toolRemovesSomeVertex(const GridBox& box, const IntervalCache& cache) {
  const GridBox r = box.intersect(cache.touched());
  if (r.empty()) return false;
  for (int y = r.lo[1]; y <= r.hi[1]; ++y)
    for (int x = r.lo[0]; x <= r.hi[0]; ++x)
      for (const Span& t : cache.line(2, x, y)) {
        // The integers strictly inside (t.lo, t.hi) that lie in [r.lo, r.hi].
        const double first = std::max(std::floor(t.lo) + 1.0, double(r.lo[2]));
        const double last = std::min(std::ceil(t.hi) - 1.0, double(r.hi[2]));
        if (first <= last) return true;
      }
  return false;
}

}  // namespace mdhd::mdh

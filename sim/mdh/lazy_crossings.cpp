#include "sim/mdh/lazy_crossings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "sim/mdh/interval_cache.h"
#include "sim/mdh/line_segments.h"

namespace mdhd::mdh {

namespace {

// One row of a map's embedded heights as the settle walks it: the row's line
// coordinates and the columns' solid counts around each edge.
struct RowWalk {
  const ThreeMap& m;
  const int* counts;  // before the cut about to be made (or now)
  const int* after;   // after it, or null
  const GridBox& region;
  int family, x, y;

  std::size_t at(int r, int e) const {
    const int nu = m.columnsU();
    return family == 0 ? static_cast<std::size_t>(r) * nu + e
                       : static_cast<std::size_t>(e) * nu + r;
  }
  // Calls due(e, k, index into the row, fresh) for every level of row r whose
  // crossing the settle computes: NaN ones (the pending cut made the edge straddle
  // there: always) and the others on edges and levels the pending cut reached, but
  // not those the cut about to be made takes away (`after`).
  // Only rows and edges with an end in the reach hold any: the pending cut changed
  // columns there only, and reached no crossing elsewhere.
  bool rowDue(int r) const {
    const int ry = m.box().lo[y] + r;
    return ry >= region.lo[y] && ry <= region.hi[y];
  }
  template <class Due>
  void walk(int r, const std::vector<double>& row, Due due) const {
    const GridBox& box = m.box();
    const int a = m.axis();
    const int eFirst = std::max(0, region.lo[x] - 1 - box.lo[x]);
    const int eEnd = std::min(m.edgesInRow(family), region.hi[x] + 1 - box.lo[x]);
    std::size_t pos = 0;
    for (int e = 0; e < eFirst; ++e) {
      int first = 0, count = 0;
      m.straddleCounts(counts[at(r, e)], counts[at(r, e + 1)], first, count);
      pos += static_cast<std::size_t>(count);
    }
    for (int e = eFirst; e < eEnd; ++e) {
      const std::size_t i0 = at(r, e), i1 = at(r, e + 1);
      int first = 0, count = 0;
      m.straddleCounts(counts[i0], counts[i1], first, count);
      if (count == 0) continue;
      int keepFirst = first, keepCount = count;
      if (after != nullptr) m.straddleCounts(after[i0], after[i1], keepFirst, keepCount);
      const int lo = std::max({first, keepFirst}),
                hi = std::min(first + count, keepFirst + keepCount);
      for (int k = lo; k < hi; ++k) {
        const std::size_t i = pos + static_cast<std::size_t>(k - first);
        const bool fresh = std::isnan(row[i]);
        if (fresh || (k >= region.lo[a] && k <= region.hi[a])) due(e, k, i, fresh);
      }
      pos += static_cast<std::size_t>(count);
    }
  }
};

}  // namespace

void settleCrossings(ThreeMap& map, const PendingCut& pending, const GridSpec& grid,
                     const int* countsAfter) {
  if (!pending || !map.threeWay()) return;
  // One store per thread, reused: a settle allocates nothing once it has grown.
  thread_local LineStore store;
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  IntervalCache cache(grid, *pending.solid, &store, (1u << u) | (1u << v));
  cache.setShared(false);
  const GridBox& box = map.box();
  const GridBox region = box.intersect(pending.reach);
  const bool up = map.direction().sign > 0;
  const std::size_t columns = static_cast<std::size_t>(map.columnsU()) * map.columnsV();
  thread_local std::vector<int> counts;
  thread_local std::vector<std::uint8_t> marks;
  thread_local std::vector<int> lineU, lineV;
  counts.resize(columns);
  const double* h = map.heightData();
  for (std::size_t i = 0; i < columns; ++i) counts[i] = map.solidCount(h[i]);
  for (int family = 0; family < 2; ++family) {
    const int x = family == 0 ? u : v, y = family == 0 ? v : u;
    const bool levelIsU = axisU(x) == a;
    const RowWalk rows{map, counts.data(), countsAfter, region, family, x, y};
    // The lines the rows will ask for, filled together where the solid answers many
    // lines for less than one by one (IntervalCache::fillLines): the same answers.
    if (cache.linesPay(x)) {
      lineU.clear();
      lineV.clear();
      marks.assign(static_cast<std::size_t>(box.points(a)), 0);
      for (int r = 0; r < map.rowCount(family); ++r) {
        if (!rows.rowDue(r)) continue;
        const int fixed = box.lo[y] + r;
        int kmin = box.points(a), kmax = -1;
        rows.walk(r, map.row(family, r), [&](int, int k, std::size_t, bool) {
          const int l = k - box.lo[a];
          marks[l] = 1;
          kmin = std::min(kmin, l), kmax = std::max(kmax, l);
        });
        for (int l = kmin; l <= kmax; ++l) {
          if (!marks[l]) continue;
          marks[l] = 0;
          lineU.push_back(levelIsU ? box.lo[a] + l : fixed);
          lineV.push_back(levelIsU ? fixed : box.lo[a] + l);
        }
      }
      if (lineU.size() > 1) cache.fillLines(x, lineU, lineV);
    }
    for (int r = 0; r < map.rowCount(family); ++r) {
      if (!rows.rowDue(r)) continue;
      std::vector<double>& row = map.row(family, r);
      const int fixed = box.lo[y] + r;
      // Up a wall the levels of the solid's prism band share one line: the same
      // question is answered once (as fast_cut.cpp's edgeCrossings does).
      const Span* lastTool = nullptr;
      std::size_t lastSize = 0;
      double lastOld = 0.0, lastValue = 0.0;
      unsigned lastStates = ~0u;
      int lastEdge = -1;
      rows.walk(r, row, [&](int e, int k, std::size_t i, bool fresh) {
        const auto tool = levelIsU ? cache.line(x, k, fixed) : cache.line(x, fixed, k);
        const double oc = row[i];
        if (!fresh && tool.empty()) return;  // an edge the solid misses keeps its crossing
        const double h0 = map.rowHeight(family, r, e), h1 = map.rowHeight(family, r, e + 1);
        const bool n0 = up ? k <= h0 : k >= h0, n1 = up ? k <= h1 : k >= h1;
        const bool o0 = fresh || n0, o1 = fresh || n1;
        const unsigned states = o0 | o1 << 1 | n0 << 2 | n1 << 3;
        const bool sameOld = oc == lastOld || (fresh && std::isnan(lastOld));
        if (!(e == lastEdge && tool.data() == lastTool && tool.size() == lastSize && sameOld &&
              states == lastStates)) {
          lastValue = edgeCrossingAfterCut(o0, o1, oc, n0, n1, box.lo[x] + e, tool);
          lastTool = tool.data(), lastSize = tool.size(), lastOld = oc, lastStates = states;
          lastEdge = e;
        }
        row[i] = lastValue;
      });
    }
  }
}

void relayoutCrossings(ThreeMap& map, const int* before, const int* after,
                       std::span<const std::size_t> moved) {
  thread_local std::vector<double> dst;
  thread_local std::vector<std::uint8_t> rowMoved;
  const int nu = map.columnsU();
  for (int family = 0; family < 2; ++family) {
    const auto at = [&](int r, int e) {
      return family == 0 ? static_cast<std::size_t>(r) * nu + e
                         : static_cast<std::size_t>(e) * nu + r;
    };
    const int n = map.edgesInRow(family) + 1;
    rowMoved.assign(static_cast<std::size_t>(map.rowCount(family)), 0);
    for (std::size_t i : moved)
      if (before[i] != after[i]) rowMoved[family == 0 ? i / nu : i % nu] = 1;
    for (int r = 0; r < map.rowCount(family); ++r) {
      if (!rowMoved[r]) continue;
      std::vector<double>& src = map.row(family, r);
      dst.clear();
      std::size_t pos = 0;
      for (int e = 0; e + 1 < n; ++e) {
        int of = 0, oc = 0, nf = 0, nc = 0;
        map.straddleCounts(before[at(r, e)], before[at(r, e + 1)], of, oc);
        map.straddleCounts(after[at(r, e)], after[at(r, e + 1)], nf, nc);
        for (int k = nf; k < nf + nc; ++k)
          dst.push_back(k >= of && k < of + oc ? src[pos + (k - of)] : std::nan(""));
        pos += static_cast<std::size_t>(oc);
      }
      // Reuse the row's storage unless it is too small or far too large (memory is
      // counted by capacity), as fast_cut.cpp's rebuildRow does.
      if (dst.size() > src.capacity() || src.capacity() > dst.size() + dst.size() / 4 + 4)
        src = std::vector<double>(dst.begin(), dst.end());
      else
        src.assign(dst.begin(), dst.end());
    }
  }
}

void settlePending(Cell& cell, const GridSpec& grid) {
  if (!cell.pending) return;
  if (cell.map) settleCrossings(*cell.map, cell.pending, grid);
  cell.pending = PendingCut{};
}

}  // namespace mdhd::mdh

#include "sim/mdh/fast_cut.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/mdh/line_segments.h"
#include "sim/mdh/vertex_rule.h"

namespace mdhd::mdh {

namespace {

struct ColumnChange {
  int iu, iv;
  double height;
};

// Per-thread buffers, so a step allocates nothing once they have grown.
struct Scratch {
  std::vector<ColumnChange> changes;
  std::vector<int> byRow;     // change indices grouped by row (counting sort)
  std::vector<int> rowStart;  // rowCount + 1 offsets into byRow
  std::vector<int> next;
  std::vector<Span> before, after, pieces;
  std::vector<double> heights, row, oldCrossings;
  std::vector<std::uint8_t> changed, was, now;
  std::vector<int> counts;     // solid vertex count of every column before the cut
  std::vector<int> newCounts;  // of the row being rebuilt, after it
};

// edgeCrossingAfterCut with its last answer kept: up a wall beside the tool, the
// levels of one edge in the tool's prism band (IntervalCache: one line slot for
// all of them) ask the same question hundreds of times per step.
class CrossingMemo {
 public:
  double operator()(bool o0, bool o1, double oc, bool n0, bool n1, int k,
                    std::span<const Span> tool) {
    const unsigned states = o0 | o1 << 1 | n0 << 2 | n1 << 3;
    if (tool.data() == tool_ && tool.size() == size_ && oc == oc_ && k == k_ && states == states_)
      return value_;
    value_ = edgeCrossingAfterCut(o0, o1, oc, n0, n1, k, tool);
    tool_ = tool.data(), size_ = tool.size(), oc_ = oc, k_ = k, states_ = states;
    return value_;
  }

 private:
  const Span* tool_ = nullptr;
  std::size_t size_ = 0;
  double oc_ = 0.0, value_ = 0.0;
  int k_ = 0;
  unsigned states_ = 0;
};

// One solid run from the base face: its far end is the column's new height.
bool heightFromRuns(const ThreeMap& m, const std::vector<Span>& runs, double& out) {
  const int a = m.axis();
  const bool up = m.direction().sign > 0;
  if (runs.empty()) {
    out = m.emptyHeight();
    return true;
  }
  const Span& run = runs.front();
  if (runs.size() > 1 || (up ? run.lo > m.box().lo[a] : run.hi < m.box().hi[a])) return false;
  out = up ? run.hi : run.lo;
  return true;
}

// The column's height after the cut in a z map, whose lines are the ones
// vertex_rule.h decides on; false if it no longer is one solid run from the
// base face. A vertex the tool does not hold strictly inside stays, even as a
// solid of zero length: every other cell holding it keeps it too.
bool cutZColumn(const ThreeMap& m, double h, std::span<const Span> tool, Scratch& s, double& out) {
  const int a = m.axis();
  const double lo = m.box().lo[a], hi = m.box().hi[a];
  const bool up = m.direction().sign > 0;
  s.before.clear();
  if (m.solidCount(h) > 0)
    s.before.push_back(up ? Span{lo, std::min(h, hi)} : Span{std::max(h, lo), hi});
  subtractOpen(s.before, tool, s.after);
  s.pieces.clear();
  for (const Span& p : s.after)
    if (std::ceil(p.lo) <= std::floor(p.hi)) s.pieces.push_back(p);  // holds a vertex
  return heightFromRuns(m, s.pieces, out);
}

// The same in an x or y map: the vertex states come from the z lines through
// them (vertex_rule.h), the new height is the crossing of the top edge as
// every cell holding that edge computes it.
bool cutSideColumn(const ThreeMap& m, double h, std::span<const Span> tool,
                   const std::array<int, 3>& base, const IntervalCache& cache, const GridBox& reach,
                   Scratch& s, double& out) {
  const int a = m.axis(), n = m.levels(), lo = m.box().lo[a];
  const bool up = m.direction().sign > 0;
  s.was.resize(n);
  s.now.resize(n);
  bool changed = false;
  std::array<int, 3> p = base;
  for (int k = 0; k < n; ++k) {
    s.was[k] = s.now[k] = m.solidAt(h, lo + k);
    if (!s.was[k] || lo + k < reach.lo[a] || lo + k > reach.hi[a]) continue;
    p[a] = lo + k;
    if (toolRemovesVertex(cache, p)) s.now[k] = 0, changed = true;
  }
  if (!changed && tool.empty()) {
    out = h;
    return true;
  }
  // Solid vertices counted from the base face must be all of them.
  int count = 0;
  while (count < n && s.now[up ? count : n - 1 - count]) ++count;
  for (int k = count; k < n; ++k)
    if (s.now[up ? k : n - 1 - k]) return false;
  if (count == 0) {
    out = m.emptyHeight();
  } else if (count == n) {
    out = m.fullHeight();
  } else {
    const int e = up ? count - 1 : n - 1 - count;  // the edge (lo + e, lo + e + 1) crosses
    const bool o0 = s.was[e], o1 = s.was[e + 1];
    out = edgeCrossingAfterCut(o0, o1, o0 != o1 ? h : std::nan(""), s.now[e], s.now[e + 1], lo + e,
                               tool);
  }
  return true;
}

int countAt(const ThreeMap& m, const Scratch& s, int family, int r, int e) {
  return s.counts[family == 0 ? r * m.columnsU() + e : e * m.columnsU() + r];
}

// Rebuilds one row of embedded heights; `heights` are the row's new parent
// heights, `changed` marks the columns that moved. Edges in [e0, e1) lie in
// the tool's box: their crossings can move even when neither column changes.
// Adds the change of the row's edge terms of the volume to `delta` (if not null).
void rebuildRow(ThreeMap& m, int family, int r, int e0, int e1, const IntervalCache& cache,
                Scratch& s, double* delta) {
  const int a = m.axis();
  const int x = family == 0 ? m.uAxis() : m.vAxis(), y = family == 0 ? m.vAxis() : m.uAxis();
  const GridBox& box = m.box();
  std::vector<double>& src = m.row(family, r);
  std::vector<double>& dst = s.row;
  dst.clear();
  const double weight = 0.5 * m.squaresAtEdge(family, r);
  std::size_t pos = 0;
  std::array<int, 3> p{};
  p[y] = box.lo[y] + r;
  CrossingMemo crossing;
  for (int e = 0; e < m.edgesInRow(family); ++e) {
    const double oh0 = m.rowHeight(family, r, e), oh1 = m.rowHeight(family, r, e + 1);
    const double nh0 = s.heights[e], nh1 = s.heights[e + 1];
    int ofirst = 0, ocount = 0, nfirst = 0, ncount = 0;
    m.straddleCounts(countAt(m, s, family, r, e), countAt(m, s, family, r, e + 1), ofirst, ocount);
    m.straddleCounts(s.newCounts[e], s.newCounts[e + 1], nfirst, ncount);
    const bool touched = s.changed[e] || s.changed[e + 1];
    const bool reached = touched || (e >= e0 && e < e1);
    const std::size_t start = dst.size();
    bool moved = touched;
    for (int i = 0; i < ncount; ++i) {
      const int k = nfirst + i;
      const bool hadOne = k >= ofirst && k < ofirst + ocount;
      double value = hadOne ? src[pos + (k - ofirst)] : std::nan("");
      if (reached) {
        p[a] = k;
        const auto tool = cache.line(x, p[axisU(x)], p[axisV(x)]);
        value = crossing(m.solidAt(oh0, k), m.solidAt(oh1, k), value, m.solidAt(nh0, k),
                         m.solidAt(nh1, k), box.lo[x] + e, tool);
        // Untouched edges keep their layout: compare with the old crossing.
        moved = moved || !(value == src[pos + i]);
      }
      dst.push_back(value);
    }
    if (moved && weight > 0.0 && delta != nullptr)
      *delta += weight * (m.edgeIntegral(nh0, nh1, box.lo[x] + e, dst.data() + start) -
                          m.edgeIntegral(oh0, oh1, box.lo[x] + e, src.data() + pos));
    pos += ocount;
  }
  // Reuse the row's storage unless it is too small or far too large (memory is
  // counted by capacity).
  if (dst.size() > src.capacity() || src.capacity() > dst.size() + dst.size() / 4 + 4)
    src = std::vector<double>(dst.begin(), dst.end());
  else
    src.assign(dst.begin(), dst.end());
}

// A row without changed columns keeps its layout: only the crossings on
// edges [e0, e1) the tool's lines reach move, in place. True if one moved;
// the change of the row's edge terms of the volume is added to `delta` (if not null).
bool moveRowCrossings(ThreeMap& m, int family, int r, int e0, int e1, const IntervalCache& cache,
                      Scratch& s, double* delta) {
  const int a = m.axis();
  const int x = family == 0 ? m.uAxis() : m.vAxis(), y = family == 0 ? m.vAxis() : m.uAxis();
  const GridBox& box = m.box();
  std::vector<double>& row = m.row(family, r);
  const double weight = 0.5 * m.squaresAtEdge(family, r);
  std::array<int, 3> p{};
  p[y] = box.lo[y] + r;
  bool moved = false;
  std::size_t pos = 0;
  CrossingMemo crossing;
  for (int e = 0; e < e1; ++e) {
    const double h0 = m.rowHeight(family, r, e), h1 = m.rowHeight(family, r, e + 1);
    int first = 0, count = 0;
    m.straddleCounts(countAt(m, s, family, r, e), countAt(m, s, family, r, e + 1), first, count);
    if (e < e0 || count == 0) {
      pos += count;
      continue;
    }
    double* c = row.data() + pos;
    if (delta != nullptr) s.oldCrossings.assign(c, c + count);
    bool edgeMoved = false;
    const bool s0 = m.solidAt(h0, first), s1 = m.solidAt(h1, first);  // alike on every level
    for (int i = 0; i < count; ++i) {
      p[a] = first + i;
      const auto tool = cache.line(x, p[axisU(x)], p[axisV(x)]);
      if (tool.empty()) continue;
      const double value = crossing(s0, s1, c[i], s0, s1, box.lo[x] + e, tool);
      if (!(value == c[i])) {
        c[i] = value;
        edgeMoved = true;
      }
    }
    if (edgeMoved && weight > 0.0 && delta != nullptr)
      *delta += weight * (m.edgeIntegral(h0, h1, box.lo[x] + e, c) -
                          m.edgeIntegral(h0, h1, box.lo[x] + e, s.oldCrossings.data()));
    moved = moved || edgeMoved;
    pos += count;
  }
  return moved;
}

// Groups the changes by row of `family` (rows along u are indexed by iv).
void groupByRow(const ThreeMap& m, int family, Scratch& s) {
  const int rows = m.rowCount(family);
  s.rowStart.assign(rows + 1, 0);
  for (const ColumnChange& c : s.changes) ++s.rowStart[(family == 0 ? c.iv : c.iu) + 1];
  for (int r = 0; r < rows; ++r) s.rowStart[r + 1] += s.rowStart[r];
  s.byRow.resize(s.changes.size());
  s.next.assign(s.rowStart.begin(), s.rowStart.end() - 1);
  for (std::size_t i = 0; i < s.changes.size(); ++i) {
    const ColumnChange& c = s.changes[i];
    s.byRow[s.next[family == 0 ? c.iv : c.iu]++] = static_cast<int>(i);
  }
}

}  // namespace

FastCut fastCut(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                double* volumeDelta) {
  thread_local Scratch s;
  if (volumeDelta != nullptr) *volumeDelta = 0.0;
  const GridBox region = map.box().intersect(reach);
  if (region.empty()) return FastCut::kUnchanged;
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  const GridBox& box = map.box();
  s.changes.clear();
  const bool up = map.direction().sign > 0;
  const double bottom = box.lo[a], top = box.hi[a];
  for (int cv = region.lo[v]; cv <= region.hi[v]; ++cv)
    for (int cu = region.lo[u]; cu <= region.hi[u]; ++cu) {
      const int iu = cu - box.lo[u], iv = cv - box.lo[v];
      const double h = map.height(iu, iv);
      // An empty column of a z map has nothing to lose: no need to ask for its line.
      if (a == 2 && map.solidCount(h) == 0) continue;
      const auto tool = cache.line(a, cu, cv);
      if (tool.empty() && a == 2) continue;
      // In a z map, most columns under the tool are not reached below their
      // top (behind the tool, above the part): they keep their height, as
      // cutZColumn would find. (Side maps take their vertices from z lines.)
      if (a == 2 && (up ? tool.front().lo >= std::min(h, top) - kToolSlack
                        : tool.back().hi <= std::max(h, bottom) + kToolSlack))
        continue;
      double nh = 0.0;
      std::array<int, 3> base{};
      base[u] = cu;
      base[v] = cv;
      const bool ok = a == 2 ? cutZColumn(map, h, tool, s, nh)
                             : cutSideColumn(map, h, tool, base, cache, reach, s, nh);
      if (!ok) return FastCut::kOverhang;
      if (!(nh == h)) s.changes.push_back({iu, iv, nh});
    }
  if (s.changes.empty() && !map.threeWay()) return FastCut::kUnchanged;
  // volume() is a sum of edge terms (1/2 per square holding the edge) minus
  // column terms (1/4 per square holding the column): the change is that of
  // the terms of the edges and columns that moved.
  // The column terms' change, `perSquare` for each square holding the column.
  const auto columnTerms = [&](double perSquare) {
    double d = 0.0;
    for (const ColumnChange& c : s.changes)
      d += perSquare * map.squaresAtColumn(c.iu, c.iv) *
           (map.columnLength(c.height) - map.columnLength(map.height(c.iu, c.iv)));
    return d;
  };
  const bool volume = volumeDelta != nullptr;
  double delta = volume ? -columnTerms(0.25) : 0.0, edgeDelta = 0.0;
  double* edges = volume ? &edgeDelta : nullptr;
  bool moved = !s.changes.empty();
  if (map.threeWay()) {
    s.counts.resize(static_cast<std::size_t>(map.columnsU()) * map.columnsV());
    for (int iv = 0; iv < map.columnsV(); ++iv)
      for (int iu = 0; iu < map.columnsU(); ++iu)
        s.counts[iv * map.columnsU() + iu] = map.solidCount(map.height(iu, iv));
    for (int family = 0; family < 2; ++family) {
      const int x = family == 0 ? u : v, y = family == 0 ? v : u;
      const int e0 = region.lo[x] - box.lo[x], e1 = region.hi[x] - box.lo[x];
      groupByRow(map, family, s);
      for (int r = 0; r < map.rowCount(family); ++r) {
        const int begin = s.rowStart[r], end = s.rowStart[r + 1];
        if (begin == end) {
          const int ry = box.lo[y] + r;
          if (ry >= region.lo[y] && ry <= region.hi[y])
            moved |= moveRowCrossings(map, family, r, e0, e1, cache, s, edges);
          continue;
        }
        const int n = map.edgesInRow(family) + 1;
        s.heights.resize(n);
        s.newCounts.resize(n);
        s.changed.assign(n, 0);
        for (int e = 0; e < n; ++e) {
          s.heights[e] = map.rowHeight(family, r, e);
          s.newCounts[e] = countAt(map, s, family, r, e);
        }
        for (int i = begin; i < end; ++i) {
          const ColumnChange& c = s.changes[s.byRow[i]];
          const int e = family == 0 ? c.iu : c.iv;
          s.heights[e] = c.height;
          s.newCounts[e] = map.solidCount(c.height);
          s.changed[e] = 1;
        }
        rebuildRow(map, family, r, e0, e1, cache, s, edges);
      }
    }
  } else if (volume) {
    delta += columnTerms(0.5);  // a plain heightmap's edge terms are its columns' means
  }
  if (!moved) return FastCut::kUnchanged;
  for (const ColumnChange& c : s.changes) map.setHeight(c.iu, c.iv, c.height);
  if (volume) *volumeDelta = edgeDelta + delta;
  return FastCut::kDone;
}

}  // namespace mdhd::mdh

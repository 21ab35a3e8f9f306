#include "sim/mdh/fast_cut.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "sim/mdh/lazy_crossings.h"
#include "sim/mdh/line_segments.h"
#include "sim/mdh/vertex_rule.h"

namespace mdhd::mdh {

namespace {

// Per-thread buffers, so a step allocates nothing once they have grown.
struct Scratch {
  std::vector<ColumnChange> changes;
  std::vector<int> byRow;     // change indices grouped by row (counting sort)
  std::vector<int> rowStart;  // rowCount + 1 offsets into byRow
  std::vector<int> next;
  std::vector<Span> before, after, pieces;
  std::vector<double> heights, oldHeights, row, oldCrossings;  // a row's, after and before
  std::vector<std::uint8_t> changed;
  std::vector<int> counts;            // solid vertex count of every column before the cut
  std::vector<int> newCounts;         // of the row being rebuilt, after it
  std::vector<double> regionHeights;  // cutColumns: a row's heights in the region
  std::vector<int> rowLines;          // the z lines a row of columns asks for
  std::vector<Span> rowSpans;         // their intervals, when the cell computes them itself
  std::vector<std::size_t> rowEnds;
  std::vector<int> newCountsMap;          // solid vertex counts after the cut, every column
  std::vector<std::uint8_t> changedMap;   // the columns that moved, every column
  std::vector<std::uint8_t> levelMarks;   // the levels a row of edges will ask for
  std::vector<int> lineU, lineV;          // the x or y lines the family loop will ask for
  std::vector<std::size_t> movedColumns;  // cutLazily: the changes' column indices
};

// The vertex rule (vertex_rule.h) for the vertices of `region` in an x or y map, each
// z line looked up once: a side map's column meets a new z line at every vertex, the
// column beside it the same lines again. Lines are asked for only when a vertex on
// them is (the same lines the rule vertex by vertex would fill).
class SideVertexRule {
 public:
  SideVertexRule(const IntervalCache& cache, const GridBox& region) : cache_(cache), r_(region) {
    nx_ = r_.points(0);
    ny_ = r_.points(1);
    nz_ = r_.points(2);
    done_.assign(static_cast<std::size_t>(nx_) * ny_, 0);
    gone_.resize(static_cast<std::size_t>(nx_) * ny_ * nz_);
  }
  bool removes(const std::array<int, 3>& p) {
    const std::size_t xy = static_cast<std::size_t>(p[1] - r_.lo[1]) * nx_ + (p[0] - r_.lo[0]);
    std::uint8_t* marks = gone_.data() + xy * nz_;
    if (!done_[xy]) {
      done_[xy] = 1;
      std::fill(marks, marks + nz_, 0);
      // The integers strictly inside a span (strictlyInside), within the region.
      for (const Span& t : cache_.line(2, p[0], p[1])) {
        const double first = std::max(std::floor(t.lo) + 1.0, double(r_.lo[2]));
        const double last = std::min(std::ceil(t.hi) - 1.0, double(r_.hi[2]));
        for (double k = first; k <= last; k += 1.0) marks[static_cast<int>(k) - r_.lo[2]] = 1;
      }
    }
    return marks[p[2] - r_.lo[2]] != 0;
  }

 private:
  const IntervalCache& cache_;
  GridBox r_;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  thread_local static std::vector<std::uint8_t> done_, gone_;
};

thread_local std::vector<std::uint8_t> SideVertexRule::done_, SideVertexRule::gone_;

// What solid counts need, held in locals: the loops below store into rows and
// scratch vectors, after which anything read through the map (its sizes, box,
// direction) would be loaded again. Heights are read a row at a time
// (ThreeMap::rowHeights) into scratch vectors.
struct Columns {
  explicit Columns(const ThreeMap& m)
      : nu(m.columnsU()),
        lo(m.box().lo[m.axis()]),
        hi(m.box().hi[m.axis()]),
        up(m.direction().sign > 0) {}
  int solidCount(double x) const { return columnSolidCount(x, lo, hi, up); }
  void straddleCounts(int f1, int f2, int& first, int& count) const {
    columnStraddle(f1, f2, lo, hi, up, first, count);
  }

  int nu, lo, hi;
  bool up;
};

// The crossings of one edge (its line along `x`) after a cut, level by level:
// level first + i gets out[i], from the crossing it had before (`oldAt(k)`, NaN
// where the edge had none) and the states of the edge's two columns before and
// after (heights oh0, oh1 -> nh0, nh1). Everything the loop needs is a local, so
// nothing is reloaded after each store. Up a wall beside the tool the levels in
// the tool's prism band share one line slot (IntervalCache), and with the same
// states and old crossing they ask edgeCrossingAfterCut the same question
// hundreds of times per step: the last answer is kept.
struct EdgeCut {
  bool up;  // the map's direction: a column of height h holds levels <= h (else >= h)
  double oh0, oh1, nh0, nh1;
  int start;  // the edge's first grid coordinate along x
};

// Returns whether any crossing differs from the one before (meaningful where the
// edge's layout is the same before and after). `keepOffLines`: a level whose
// line the tool misses keeps its crossing untouched (both columns unchanged).
template <bool keepOffLines, class OldAt>
bool edgeCrossings(const EdgeCut& c, int first, int count, const IntervalCache& cache, int x,
                   int fixed, bool levelIsU, OldAt oldAt, double* out) {
  const Span* lastTool = nullptr;
  std::size_t lastSize = 0;
  double lastOld = 0.0, lastValue = 0.0;
  unsigned lastStates = ~0u;
  bool changed = false;
  for (int i = 0; i < count; ++i) {
    const int k = first + i;
    const double oc = oldAt(k);
    const auto tool = levelIsU ? cache.line(x, k, fixed) : cache.line(x, fixed, k);
    if (keepOffLines && tool.empty()) {
      out[i] = oc;
      continue;
    }
    const bool o0 = c.up ? k <= c.oh0 : k >= c.oh0, o1 = c.up ? k <= c.oh1 : k >= c.oh1;
    const bool n0 = c.up ? k <= c.nh0 : k >= c.nh0, n1 = c.up ? k <= c.nh1 : k >= c.nh1;
    const unsigned states = o0 | o1 << 1 | n0 << 2 | n1 << 3;
    // NaN (no crossing before) must match NaN: a wall the cut opens has none at any level.
    const bool sameOld = oc == lastOld || (std::isnan(oc) && std::isnan(lastOld));
    if (!(tool.data() == lastTool && tool.size() == lastSize && sameOld && states == lastStates)) {
      lastValue = edgeCrossingAfterCut(o0, o1, oc, n0, n1, c.start, tool);
      lastTool = tool.data(), lastSize = tool.size(), lastOld = oc, lastStates = states;
    }
    changed = changed || !(lastValue == oc);
    out[i] = lastValue;
  }
  return changed;
}

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
  if (tool.size() == 1 && m.solidCount(h) > 0) {
    // The usual column: one solid run less one open tool span, as subtractOpen, the
    // vertex filter and heightFromRuns below make it, without their vectors.
    const Span c = up ? Span{lo, std::min(h, hi)} : Span{std::max(h, lo), hi};
    const Span t = tool[0];
    Span piece[2];
    int n = 0;
    if (t.hi <= c.lo || t.lo >= c.hi) {
      piece[n++] = c;
    } else {
      if (t.lo >= c.lo) piece[n++] = {c.lo, t.lo};
      if (!(t.hi > c.hi)) piece[n++] = {t.hi, c.hi};
    }
    int kept = 0;
    for (int i = 0; i < n; ++i)
      if (std::ceil(piece[i].lo) <= std::floor(piece[i].hi)) piece[kept++] = piece[i];
    if (kept == 0) {
      out = m.emptyHeight();
      return true;
    }
    if (kept > 1 || (up ? piece[0].lo > lo : piece[0].hi < hi)) return false;
    out = up ? piece[0].hi : piece[0].lo;
    return true;
  }
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
                   const std::array<int, 3>& base, SideVertexRule& rule, const GridBox& reach,
                   double& out) {
  const int a = m.axis(), n = m.levels(), lo = m.box().lo[a];
  const bool up = m.direction().sign > 0;
  // The column's solid vertices before the cut are one run from the base face,
  // levels [s0, s1] (up: from 0; down: to n - 1), exactly as solidAt says.
  int s0 = 0, s1 = n - 1;
  if (up) {
    s1 = static_cast<int>(std::clamp(std::floor(h - lo), -1.0, n - 1.0));
    while (s1 >= 0 && !m.solidAt(h, lo + s1)) --s1;
    while (s1 + 1 < n && m.solidAt(h, lo + s1 + 1)) ++s1;
  } else {
    s0 = static_cast<int>(std::clamp(std::ceil(h - lo), 0.0, double(n)));
    while (s0 < n && !m.solidAt(h, lo + s0)) ++s0;
    while (s0 > 0 && m.solidAt(h, lo + s0 - 1)) --s0;
  }
  // Only solid vertices in the reach can go (the vertex rule: along their z lines).
  // Walked from the base: after the first that goes, every solid one must go too, or
  // the column is no longer one run from the base.
  const int c0 = std::max(s0, reach.lo[a] - lo), c1 = std::min(s1, reach.hi[a] - lo);
  std::array<int, 3> p = base;
  int first = -1;  // the first vertex removed, counted from the base
  for (int i = 0; i <= c1 - c0; ++i) {
    const int k = up ? c0 + i : c1 - i;
    p[a] = lo + k;
    if (rule.removes(p)) {
      if (first < 0) first = k;
    } else if (first >= 0) {
      return false;
    }
  }
  if (first < 0 && tool.empty()) {
    out = h;
    return true;
  }
  // Solid vertices beyond the reach stay: past a removed one that is an overhang.
  if (first >= 0 && (up ? s1 > c1 : s0 < c0)) return false;
  // Solid vertices counted from the base face after the cut.
  const int count = first >= 0 ? (up ? first : n - 1 - first) : s1 - s0 + 1;
  if (count == 0) {
    out = m.emptyHeight();
  } else if (count == n) {
    out = m.fullHeight();
  } else {
    // The edge (lo + e, lo + e + 1) crosses: its base-side end is kept, the other not.
    const int e = up ? count - 1 : n - 1 - count;
    const bool o0 = e >= s0 && e <= s1, o1 = e + 1 >= s0 && e + 1 <= s1;
    out = edgeCrossingAfterCut(o0, o1, o0 != o1 ? h : std::nan(""), up, !up, lo + e, tool);
  }
  return true;
}

int countAt(const Columns& c, const Scratch& s, int family, int r, int e) {
  return s.counts[family == 0 ? r * c.nu + e : e * c.nu + r];
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
  const bool up = m.direction().sign > 0, levelIsU = axisU(x) == a;
  const int fixed = box.lo[y] + r, edges = m.edgesInRow(family);
  const Columns cols(m);
  std::vector<double>& src = m.row(family, r);
  std::vector<double>& dst = s.row;
  dst.clear();
  const double weight = 0.5 * m.squaresAtEdge(family, r);
  std::size_t pos = 0;
  for (int e = 0; e < edges; ++e) {
    const double oh0 = s.oldHeights[e], oh1 = s.oldHeights[e + 1];
    const double nh0 = s.heights[e], nh1 = s.heights[e + 1];
    int ofirst = 0, ocount = 0, nfirst = 0, ncount = 0;
    cols.straddleCounts(countAt(cols, s, family, r, e), countAt(cols, s, family, r, e + 1), ofirst,
                        ocount);
    cols.straddleCounts(s.newCounts[e], s.newCounts[e + 1], nfirst, ncount);
    const bool touched = s.changed[e] || s.changed[e + 1];
    const bool reached = touched || (e >= e0 && e < e1);
    const std::size_t start = dst.size();
    dst.resize(start + static_cast<std::size_t>(ncount));
    double* out = dst.data() + start;
    const double* old = src.data() + pos;
    if (!reached) {
      // Neither column moved and the tool is not here: the same crossings.
      std::copy_n(old, ocount, out);
    } else {
      const auto oldAt = [&](int k) {
        return k >= ofirst && k < ofirst + ocount ? old[k - ofirst] : std::nan("");
      };
      // Untouched edges keep their layout: `changed` compares level by level.
      const bool changed = edgeCrossings<false>({up, oh0, oh1, nh0, nh1, box.lo[x] + e}, nfirst,
                                                ncount, cache, x, fixed, levelIsU, oldAt, out);
      const bool moved = touched || changed;
      if (moved && weight > 0.0 && delta != nullptr)
        *delta += weight * (m.edgeIntegral(nh0, nh1, box.lo[x] + e, out) -
                            m.edgeIntegral(oh0, oh1, box.lo[x] + e, old));
    }
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
// edges [e0, e1) at levels [k0, k1] (the cut's reach) can move, in place. True
// if one moved; the change of the row's edge terms of the volume is added to
// `delta` (if not null).
bool moveRowCrossings(ThreeMap& m, int family, int r, int e0, int e1, int k0, int k1,
                      const IntervalCache& cache, Scratch& s, double* delta) {
  const int a = m.axis();
  const int x = family == 0 ? m.uAxis() : m.vAxis(), y = family == 0 ? m.vAxis() : m.uAxis();
  const GridBox& box = m.box();
  const bool up = m.direction().sign > 0, levelIsU = axisU(x) == a;
  const int fixed = box.lo[y] + r;
  const Columns cols(m);
  const TileReader heights = m.heights();  // no height is stored while it lives
  std::vector<double>& row = m.row(family, r);
  const double weight = 0.5 * m.squaresAtEdge(family, r);
  bool moved = false;
  std::size_t pos = 0;
  for (int e = 0; e < e1; ++e) {
    int first = 0, count = 0;
    cols.straddleCounts(countAt(cols, s, family, r, e), countAt(cols, s, family, r, e + 1), first,
                        count);
    const int lo = std::max(first, k0), hi = std::min(first + count - 1, k1);
    if (e < e0 || lo > hi) {
      pos += count;
      continue;
    }
    const double h0 = heights.get(family == 0 ? e : r, family == 0 ? r : e);
    const double h1 = heights.get(family == 0 ? e + 1 : r, family == 0 ? r : e + 1);
    double* c = row.data() + pos;
    const bool integrate = weight > 0.0 && delta != nullptr;
    if (integrate) s.oldCrossings.assign(c, c + count);
    // In place: a level reads its crossing before it writes it.
    double* from = c + (lo - first);
    const bool edgeMoved = edgeCrossings<true>(
        {up, h0, h1, h0, h1, box.lo[x] + e}, lo, hi - lo + 1, cache, x, fixed, levelIsU,
        [&](int k) { return from[k - lo]; }, from);
    if (edgeMoved && integrate)
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

// The columns' solid counts after the cut and which columns moved, over the whole
// map (fillFamilyLines reads rows of either family from them). `counts` must hold
// the counts before the cut.
void columnsAfterCut(const ThreeMap& m, Scratch& s) {
  const Columns cols(m);
  const std::size_t columns = static_cast<std::size_t>(m.columnsU()) * m.columnsV();
  s.newCountsMap.assign(s.counts.begin(), s.counts.begin() + static_cast<std::ptrdiff_t>(columns));
  s.changedMap.assign(columns, 0);
  for (const ColumnChange& c : s.changes) {
    const std::size_t i = static_cast<std::size_t>(c.iv) * cols.nu + c.iu;
    s.newCountsMap[i] = cols.solidCount(c.height);
    s.changedMap[i] = 1;
  }
}

// Fills the lines of `family` that the row loop of fastCut will ask for (rebuildRow:
// every level a reached edge straddles after the cut; moveRowCrossings: the levels
// in reach an edge in reach straddles) with one IntervalCache::fillLines, where the
// solid answers many lines for less than one by one: the same answers, computed
// together. Needs groupByRow's rows of the family and columnsAfterCut. A prefill
// only: a line it misses is still asked by line(), one too many costs time; neither
// changes an answer (test AFastCutAsksItsCrossingLinesInBatches holds that it misses
// none). Kept out of line: inlined, it tips fastCut's own calls out of line.
[[gnu::noinline]] void fillFamilyLines(const ThreeMap& m, const IntervalCache& cache,
                                       const GridBox& region, int family, Scratch& s) {
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  const int x = family == 0 ? u : v, y = family == 0 ? v : u;
  const GridBox& box = m.box();
  const Columns cols(m);
  const int levels = m.levels(), base = box.lo[a];
  const bool levelIsU = axisU(x) == a;
  const int e0 = region.lo[x] - box.lo[x], e1 = region.hi[x] - box.lo[x];
  const int edges = m.edgesInRow(family);
  const auto at = [&](int r, int e) {
    return family == 0 ? static_cast<std::size_t>(r) * cols.nu + e
                       : static_cast<std::size_t>(e) * cols.nu + r;
  };
  // A row's marks span few of a tall cell's levels: only the span marked is scanned,
  // and cleared as it is, so the marks start each row all clear.
  int kmin = levels, kmax = -1;
  const auto mark = [&](int first, int count, int k0, int k1) {
    const int lo = std::max({first, k0, base}) - base;
    const int hi = std::min({first + count - 1, k1, base + levels - 1}) - base;
    for (int k = lo; k <= hi; ++k) s.levelMarks[k] = 1;
    if (lo <= hi) kmin = std::min(kmin, lo), kmax = std::max(kmax, hi);
  };
  s.levelMarks.assign(static_cast<std::size_t>(levels), 0);
  s.lineU.clear();
  s.lineV.clear();
  for (int r = 0; r < m.rowCount(family); ++r) {
    const bool rowChanged = s.rowStart[r] != s.rowStart[r + 1];
    const int ry = box.lo[y] + r;
    if (!rowChanged && (ry < region.lo[y] || ry > region.hi[y])) continue;
    kmin = levels, kmax = -1;
    int first = 0, count = 0;
    if (rowChanged) {
      for (int e = 0; e < edges; ++e) {
        const std::size_t i0 = at(r, e), i1 = at(r, e + 1);
        if (!(s.changedMap[i0] || s.changedMap[i1] || (e >= e0 && e < e1))) continue;
        cols.straddleCounts(s.newCountsMap[i0], s.newCountsMap[i1], first, count);
        mark(first, count, first, first + count - 1);
      }
    } else {
      for (int e = e0; e < e1; ++e) {
        cols.straddleCounts(s.counts[at(r, e)], s.counts[at(r, e + 1)], first, count);
        mark(first, count, region.lo[a], region.hi[a]);
      }
    }
    for (int k = kmin; k <= kmax; ++k) {
      if (!s.levelMarks[k]) continue;
      s.levelMarks[k] = 0;
      s.lineU.push_back(levelIsU ? base + k : ry);
      s.lineV.push_back(levelIsU ? ry : base + k);
    }
  }
  if (s.lineU.size() > 1) cache.fillLines(x, s.lineU, s.lineV);
}

// The columns the cut reaches, in s.changes (those whose height moves); false if
// one is no longer a single solid run from the base face (an overhang).
bool cutColumns(const ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                const GridBox& region, Scratch& s) {
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  const GridBox& box = map.box();
  s.changes.clear();
  const bool up = map.direction().sign > 0;
  const double bottom = box.lo[a], top = box.hi[a];
  s.regionHeights.resize(static_cast<std::size_t>(region.points(u)));
  // A z column whose top lies below the tool's lowest point (above its highest in
  // a -z map) keeps its height: no need to ask for its line. The margin covers
  // the intervals' snapping (1e-9) and rounding against the solid's bounds.
  constexpr double kMargin = 1e-6;
  const double below = up ? cache.lowest(2) - kMargin : cache.highest(2) + kMargin;
  const auto underTool = [&](double h) { return up ? h <= below : h >= below; };
  const bool rowFill = a == 2 && cache.rowsPay(a);
  // A cell as tall as the stock is the only one to ask for its z lines (but for the
  // columns on its sides, which a neighbour computes again, to the same bits): it
  // computes them itself, without the shared slots' claims and stores.
  const bool ownLines = rowFill && box.lo[a] == 0 && box.hi[a] == cache.grid().cubes[a];
  std::optional<SideVertexRule> rule;
  if (a != 2) rule.emplace(cache, region);
  for (int cv = region.lo[v]; cv <= region.hi[v]; ++cv) {
    // The row's heights in the region, read once.
    map.rowHeights(0, cv - box.lo[v], region.lo[u] - box.lo[u], region.hi[u] - box.lo[u] + 1,
                   s.regionHeights.data());
    if (rowFill) {
      // The row's lines that the loop below will ask for, filled body by body in one
      // go (IntervalCache::fillRow): the same answers, for less per line.
      s.rowLines.clear();
      for (int cu = region.lo[u]; cu <= region.hi[u]; ++cu)
        if (!underTool(s.regionHeights[cu - region.lo[u]])) s.rowLines.push_back(cu);
      if (ownLines)
        cache.rowSpans(a, cv, s.rowLines, s.rowSpans, s.rowEnds);
      else if (s.rowLines.size() > 1)
        cache.fillRow(a, cv, s.rowLines);
    }
    std::size_t line = 0;  // ownLines: the next of the row's lines
    for (int cu = region.lo[u]; cu <= region.hi[u]; ++cu) {
      const int iu = cu - box.lo[u], iv = cv - box.lo[v];
      const double h = s.regionHeights[cu - region.lo[u]];
      // An empty column of a z map has nothing to lose: no need to ask for its line.
      if (a == 2 && underTool(h)) continue;
      std::span<const Span> tool;
      if (ownLines) {  // the same columns as the row's lines, in the same order
        const std::size_t from = line == 0 ? 0 : s.rowEnds[line - 1];
        tool = std::span<const Span>(s.rowSpans.data() + from, s.rowEnds[line] - from);
        ++line;
      } else {
        tool = cache.line(a, cu, cv);
      }
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
                             : cutSideColumn(map, h, tool, base, *rule, reach, nh);
      if (!ok) return false;
      if (!(nh == h)) s.changes.push_back({iu, iv, nh});
    }
  }
  return true;
}

}  // namespace

FastCut fastCut(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                double* volumeDelta, bool* columnsMoved) {
  thread_local Scratch s;
  if (volumeDelta != nullptr) *volumeDelta = 0.0;
  if (columnsMoved != nullptr) *columnsMoved = false;
  const GridBox region = map.box().intersect(reach);
  if (region.empty()) return FastCut::kUnchanged;
  if (!cutColumns(map, cache, reach, region, s)) return FastCut::kOverhang;
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  const GridBox& box = map.box();
  const Columns cols(map);
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
  // Corners read off their columns (ThreeMap::cornerCorrection) can change wherever a
  // column or an edge did: in the region and the squares around it.
  const int cu0 = std::max(region.lo[u] - box.lo[u] - 1, 0);
  const int cu1 = std::min(region.hi[u] - box.lo[u] + 1, map.columnsU() - 1);
  const int cv0 = std::max(region.lo[v] - box.lo[v] - 1, 0);
  const int cv1 = std::min(region.hi[v] - box.lo[v] + 1, map.columnsV() - 1);
  const bool corners = volume && map.threeWay();
  double delta = volume ? -columnTerms(0.25) : 0.0, edgeDelta = 0.0;
  if (corners) delta -= map.cornerCorrection(cu0, cu1, cv0, cv1);
  double* edges = volume ? &edgeDelta : nullptr;
  bool moved = !s.changes.empty();
  if (map.threeWay()) {
    const std::size_t columns = static_cast<std::size_t>(map.columnsU()) * map.columnsV();
    s.counts.resize(columns);
    int* counts = s.counts.data();
    map.solidCounts(counts);
    // x and y lines in batches where the solid answers them so (3-axis batches).
    const bool batches[2] = {cache.linesPay(u), cache.linesPay(v)};
    if (batches[0] || batches[1]) columnsAfterCut(map, s);
    for (int family = 0; family < 2; ++family) {
      const int x = family == 0 ? u : v, y = family == 0 ? v : u;
      const int e0 = region.lo[x] - box.lo[x], e1 = region.hi[x] - box.lo[x];
      groupByRow(map, family, s);
      if (batches[family]) fillFamilyLines(map, cache, region, family, s);
      for (int r = 0; r < map.rowCount(family); ++r) {
        const int begin = s.rowStart[r], end = s.rowStart[r + 1];
        if (begin == end) {
          const int ry = box.lo[y] + r;
          if (ry >= region.lo[y] && ry <= region.hi[y])
            moved |= moveRowCrossings(map, family, r, e0, e1, region.lo[a], region.hi[a], cache, s,
                                      edges);
          continue;
        }
        const int n = map.edgesInRow(family) + 1;
        s.oldHeights.resize(n);
        map.rowHeights(family, r, 0, n, s.oldHeights.data());
        s.heights.assign(s.oldHeights.begin(), s.oldHeights.end());
        s.newCounts.resize(n);
        s.changed.assign(n, 0);
        for (int e = 0; e < n; ++e) s.newCounts[e] = countAt(cols, s, family, r, e);
        for (int i = begin; i < end; ++i) {
          const ColumnChange& c = s.changes[s.byRow[i]];
          const int e = family == 0 ? c.iu : c.iv;
          s.heights[e] = c.height;
          s.newCounts[e] = cols.solidCount(c.height);
          s.changed[e] = 1;
        }
        rebuildRow(map, family, r, e0, e1, cache, s, edges);
      }
    }
  } else if (volume) {
    delta += columnTerms(0.5);  // a plain heightmap's edge terms are its columns' means
  }
  if (!moved) return FastCut::kUnchanged;
  if (columnsMoved != nullptr) *columnsMoved = !s.changes.empty();
  for (const ColumnChange& c : s.changes) map.setHeight(c.iu, c.iv, c.height);
  if (corners) delta += map.cornerCorrection(cu0, cu1, cv0, cv1);
  if (volume) *volumeDelta = edgeDelta + delta;
  return FastCut::kDone;
}

FastCut lazyColumns(const ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                    std::vector<ColumnChange>& changes) {
  thread_local Scratch s;
  const GridBox region = map.box().intersect(reach);
  if (region.empty()) return FastCut::kUnchanged;
  if (!cutColumns(map, cache, reach, region, s)) return FastCut::kOverhang;
  changes.assign(s.changes.begin(), s.changes.end());
  return FastCut::kDone;
}

void cutLazily(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
               std::span<const ColumnChange> changes,
               const std::shared_ptr<const geom::LineSolid>& solid, PendingCuts& pending) {
  thread_local Scratch s;
  const GridBox region = map.box().intersect(reach);
  // Generations are tags in NaNs' low bits: start again (all computed) long before they wrap.
  if (pending.generation >= 0xffff0000u) settleCrossings(map, pending, cache.grid());
  s.changes.assign(changes.begin(), changes.end());
  const Columns cols(map);
  const std::size_t columns = static_cast<std::size_t>(map.columnsU()) * map.columnsV();
  s.counts.resize(columns);
  map.solidCounts(s.counts.data());
  columnsAfterCut(map, s);
  // The pending cuts' crossings first, on the heights they left, where this cut keeps them.
  advanceCrossings(map, pending, cache.grid(), s.counts.data(), s.newCountsMap.data());
  const std::uint32_t generation = pending.generation + 1;
  s.movedColumns.clear();
  for (const ColumnChange& c : s.changes)
    s.movedColumns.push_back(static_cast<std::size_t>(c.iv) * cols.nu + c.iu);
  relayoutCrossings(map, s.counts.data(), s.newCountsMap.data(), s.movedColumns,
                    pendingCrossing(generation));
  pending.cuts[pending.count++] = PendingCut{solid, region, generation};
  pending.generation = generation;
  for (std::size_t k = 0; k < s.changes.size(); ++k) {
    const ColumnChange& c = s.changes[k];
    const std::size_t i = s.movedColumns[k];
    map.setHeight(c.iu, c.iv, c.height, s.counts[i], s.newCountsMap[i]);
  }
}

FastCut fastCutLazy(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                    const std::shared_ptr<const geom::LineSolid>& solid, PendingCuts& pending,
                    bool* columnsMoved) {
  thread_local std::vector<ColumnChange> changes;
  const FastCut r = lazyColumns(map, cache, reach, changes);
  if (columnsMoved != nullptr) *columnsMoved = r == FastCut::kDone && !changes.empty();
  if (r == FastCut::kDone) cutLazily(map, cache, reach, changes, solid, pending);
  return r;
}

}  // namespace mdhd::mdh

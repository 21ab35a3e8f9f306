#include "sim/mdh/fast_cut.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/mdh/line_segments.h"

namespace mdhd::mdh {

namespace {

struct ColumnChange {
  int iu, iv;
  double height;
};

// The column's height after the cut; false if it no longer is one solid run
// from the heightmap's base face.
bool cutColumn(const ThreeMap& m, double h, std::span<const Span> tool, std::vector<Span>& before,
               std::vector<Span>& after, double& out) {
  const int a = m.axis();
  const double lo = m.box().lo[a], hi = m.box().hi[a];
  const bool up = m.direction().sign > 0;
  before.clear();
  if (m.solidCount(h) > 0)
    before.push_back(up ? Span{lo, std::min(h, hi)} : Span{std::max(h, lo), hi});
  subtractOpen(before, tool, after);
  const Span* run = nullptr;
  int runs = 0;
  for (const Span& s : after) {
    if (s.hi - s.lo <= kZeroLength || std::ceil(s.lo) > std::floor(s.hi)) continue;  // no vertex
    run = &s;
    ++runs;
  }
  if (runs == 0) {
    out = m.emptyHeight();
    return true;
  }
  if (runs > 1 || (up ? run->lo > lo : run->hi < hi)) return false;
  out = up ? run->hi : run->lo;
  return true;
}

// Rebuilds one row of embedded heights; `heights` are the row's new parent
// heights, `changed` marks the columns that moved. Edges in [e0, e1) lie in
// the tool's box: their crossings can move even when neither column changes.
void rebuildRow(ThreeMap& m, int family, int r, const std::vector<double>& heights,
                const std::vector<std::uint8_t>& changed, int e0, int e1,
                const IntervalCache& cache, std::vector<Span>& pieces) {
  const int a = m.axis();
  const int x = family == 0 ? m.uAxis() : m.vAxis(), y = family == 0 ? m.vAxis() : m.uAxis();
  const GridBox& box = m.box();
  const std::vector<double>& src = m.row(family, r);
  std::vector<double> dst;
  dst.reserve(src.size() + 16);
  std::size_t pos = 0;
  std::array<int, 3> p{};
  p[y] = box.lo[y] + r;
  for (int e = 0; e < m.edgesInRow(family); ++e) {
    const double oh0 = m.rowHeight(family, r, e), oh1 = m.rowHeight(family, r, e + 1);
    const double nh0 = heights[e], nh1 = heights[e + 1];
    int ofirst = 0, ocount = 0, nfirst = 0, ncount = 0;
    m.straddle(oh0, oh1, ofirst, ocount);
    m.straddle(nh0, nh1, nfirst, ncount);
    const bool touched = changed[e] || changed[e + 1];
    const bool reached = touched || (e >= e0 && e < e1);
    for (int i = 0; i < ncount; ++i) {
      const int k = nfirst + i;
      const bool hadOne = k >= ofirst && k < ofirst + ocount;
      double value = hadOne ? src[pos + (k - ofirst)] : std::nan("");
      if (reached) {
        p[a] = k;
        const auto tool = cache.line(x, p[axisU(x)], p[axisV(x)]);
        value = edgeCrossingAfterCut(m.solidAt(oh0, k), m.solidAt(oh1, k), value, m.solidAt(nh0, k),
                                     m.solidAt(nh1, k), box.lo[x] + e, tool, pieces);
      }
      dst.push_back(value);
    }
    pos += ocount;
  }
  dst.shrink_to_fit();
  m.row(family, r) = std::move(dst);
}

// A row without changed columns keeps its layout: only the crossings on
// edges [e0, e1) the tool's lines reach move, in place. True if one moved.
bool moveRowCrossings(ThreeMap& m, int family, int r, int e0, int e1, const IntervalCache& cache,
                      std::vector<Span>& pieces) {
  const int a = m.axis();
  const int x = family == 0 ? m.uAxis() : m.vAxis(), y = family == 0 ? m.vAxis() : m.uAxis();
  const GridBox& box = m.box();
  std::vector<double>& row = m.row(family, r);
  std::array<int, 3> p{};
  p[y] = box.lo[y] + r;
  bool moved = false;
  std::size_t pos = 0;
  for (int e = 0; e < e1; ++e) {
    const double h0 = m.rowHeight(family, r, e), h1 = m.rowHeight(family, r, e + 1);
    int first = 0, count = 0;
    m.straddle(h0, h1, first, count);
    for (int i = 0; e >= e0 && i < count; ++i) {
      const int k = first + i;
      p[a] = k;
      const auto tool = cache.line(x, p[axisU(x)], p[axisV(x)]);
      if (tool.empty()) continue;
      const bool s0 = m.solidAt(h0, k), s1 = m.solidAt(h1, k);
      double& c = row[pos + i];
      const double value = edgeCrossingAfterCut(s0, s1, c, s0, s1, box.lo[x] + e, tool, pieces);
      if (!(value == c)) {
        c = value;
        moved = true;
      }
    }
    pos += count;
  }
  return moved;
}

}  // namespace

FastCut fastCut(ThreeMap& map, const IntervalCache& cache, double& volumeDelta) {
  volumeDelta = 0.0;
  const GridBox region = map.box().intersect(cache.touched());
  if (region.empty()) return FastCut::kUnchanged;
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  const GridBox& box = map.box();
  std::vector<ColumnChange> changes;
  std::vector<Span> before, after;
  for (int cv = region.lo[v]; cv <= region.hi[v]; ++cv)
    for (int cu = region.lo[u]; cu <= region.hi[u]; ++cu) {
      const auto tool = cache.line(a, cu, cv);
      if (tool.empty()) continue;
      const int iu = cu - box.lo[u], iv = cv - box.lo[v];
      const double h = map.height(iu, iv);
      double nh = 0.0;
      if (!cutColumn(map, h, tool, before, after, nh)) return FastCut::kOverhang;
      if (!(nh == h)) changes.push_back({iu, iv, nh});
    }
  if (changes.empty() && !map.threeWay()) return FastCut::kUnchanged;
  // The squares around the tool's columns are all the volume that moves: the
  // changed columns' and those of embedded crossings the tool moves alone.
  const int u0 = std::max(0, region.lo[u] - box.lo[u] - 1);
  const int v0 = std::max(0, region.lo[v] - box.lo[v] - 1);
  const int u1 = std::min(map.columnsU() - 1, region.hi[u] - box.lo[u] + 1);
  const int v1 = std::min(map.columnsV() - 1, region.hi[v] - box.lo[v] + 1);
  const double volumeBefore = map.squaresVolume(u0, u1, v0, v1);
  bool moved = !changes.empty();
  if (map.threeWay()) {
    std::vector<Span> pieces;
    std::vector<double> heights;
    std::vector<std::uint8_t> changed;
    for (int family = 0; family < 2; ++family) {
      const int x = family == 0 ? u : v, y = family == 0 ? v : u;
      const int e0 = region.lo[x] - box.lo[x], e1 = region.hi[x] - box.lo[x];
      std::vector<std::vector<int>> byRow(map.rowCount(family));
      for (std::size_t i = 0; i < changes.size(); ++i)
        byRow[family == 0 ? changes[i].iv : changes[i].iu].push_back(static_cast<int>(i));
      for (int r = 0; r < map.rowCount(family); ++r) {
        if (byRow[r].empty()) {
          const int ry = box.lo[y] + r;
          if (ry >= region.lo[y] && ry <= region.hi[y])
            moved |= moveRowCrossings(map, family, r, e0, e1, cache, pieces);
          continue;
        }
        const int n = map.edgesInRow(family) + 1;
        heights.resize(n);
        changed.assign(n, 0);
        for (int e = 0; e < n; ++e) heights[e] = map.rowHeight(family, r, e);
        for (int i : byRow[r]) {
          const ColumnChange& c = changes[i];
          const int e = family == 0 ? c.iu : c.iv;
          heights[e] = c.height;
          changed[e] = 1;
        }
        rebuildRow(map, family, r, heights, changed, e0, e1, cache, pieces);
      }
    }
  }
  if (!moved) return FastCut::kUnchanged;
  for (const ColumnChange& c : changes) map.setHeight(c.iu, c.iv, c.height);
  volumeDelta = map.squaresVolume(u0, u1, v0, v1) - volumeBefore;
  return FastCut::kDone;
}

bool toolReachesSolid(const GridBox& box, int axis, const IntervalCache& cache) {
  const GridBox region = box.intersect(cache.touched());
  if (region.empty()) return false;
  const int u = axisU(axis), v = axisV(axis);
  const double lo = box.lo[axis], hi = box.hi[axis];
  for (int cv = region.lo[v]; cv <= region.hi[v]; ++cv)
    for (int cu = region.lo[u]; cu <= region.hi[u]; ++cu)
      for (const Span& t : cache.line(axis, cu, cv))
        if (std::min(t.hi, hi) - std::max(t.lo, lo) > kZeroLength) return true;
  return false;
}

}  // namespace mdhd::mdh

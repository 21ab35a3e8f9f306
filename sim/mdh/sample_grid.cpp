#include "sim/mdh/sample_grid.h"

#include <cmath>

#include "sim/mdh/line_segments.h"
#include "sim/mdh/vertex_rule.h"

namespace mdhd::mdh {

namespace {

const double kNaN = std::nan("");

// Vertex with coordinate `level` on axis a, `cu` on axisU(a), `cv` on axisV(a).
std::array<int, 3> vertex(int a, int level, int cu, int cv) {
  std::array<int, 3> p{};
  p[a] = level;
  p[axisU(a)] = cu;
  p[axisV(a)] = cv;
  return p;
}

}  // namespace

SampleGrid::SampleGrid(const GridBox& box) : box_(box) {
  for (int a = 0; a < 3; ++a) n_[a] = box.points(a);
  const std::size_t count = static_cast<std::size_t>(box.pointCount());
  state_.assign(count, 0);
  for (auto& c : cross_) c.assign(count, kNaN);
}

SampleGrid SampleGrid::solid(const GridBox& box) {
  SampleGrid g(box);
  std::fill(g.state_.begin(), g.state_.end(), kSolid);
  return g;
}

SampleGrid SampleGrid::decode(const ThreeMap& map, const GridBox& sub) {
  SampleGrid g(sub);
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  const GridBox& box = map.box();
  // Column by column, walked with a stride (states start empty, crossings NaN): one
  // test a vertex, the crossing where the state changes.
  const std::size_t along = g.stride(a);
  for (int cv = sub.lo[v]; cv <= sub.hi[v]; ++cv) {
    for (int cu = sub.lo[u]; cu <= sub.hi[u]; ++cu) {
      const int iu = cu - box.lo[u], iv = cv - box.lo[v];
      bool up = false;
      const double h = map.column(iu, iv, up);
      const auto solidAt = [&](int k) { return up ? k <= h : k >= h; };
      std::size_t i = g.index(vertex(a, sub.lo[a], cu, cv));
      bool before = solidAt(sub.lo[a]);
      for (int k = sub.lo[a]; k <= sub.hi[a]; ++k, i += along) {
        if (before) g.state_[i] = kSolid;
        if (k == sub.hi[a]) break;
        const bool next = solidAt(k + 1);
        if (next != before) g.cross_[a][i] = h;
        before = next;
      }
    }
  }
  // A row's heights, sides and solid counts read once (the heights are in tiles).
  thread_local std::vector<double> heights;
  thread_local std::vector<int> counts;
  thread_local std::vector<std::uint8_t> ups;
  const int lo = box.lo[a], hi = box.hi[a];
  for (int family = 0; family < 2; ++family) {
    const int x = family == 0 ? u : v;  // the edges' axis
    const int y = family == 0 ? v : u;  // the rows' axis
    const int n = map.edgesInRow(family) + 1;
    heights.resize(n);
    counts.resize(n);
    ups.resize(n);
    for (int r = sub.lo[y]; r <= sub.hi[y]; ++r) {
      const int ri = r - box.lo[y];
      const std::vector<double>* row = map.threeWay() ? &map.row(family, ri) : nullptr;
      map.rowColumns(family, ri, n, heights.data(), ups.data(), counts.data());
      std::size_t pos = 0;
      for (int e = 0; e + 1 < n; ++e) {
        const double h0 = heights[e], h1 = heights[e + 1];
        const ColumnStraddle st =
            columnsStraddle(counts[e], ups[e] != 0, counts[e + 1], ups[e + 1] != 0, lo, hi);
        const int count = st.total();
        const int c = box.lo[x] + e;
        if (c >= sub.lo[x] && c + 1 <= sub.hi[x]) {
          for (int i = 0; i < count; ++i) {
            const int k = st.level(i);
            if (k < sub.lo[a] || k > sub.hi[a]) continue;
            const double value = row ? (*row)[pos + i] : map.interpolatedCrossing(h0, h1, c, k);
            std::array<int, 3> p{};
            p[a] = k;
            p[x] = c;
            p[y] = r;
            g.cross_[x][g.index(p)] = value;
          }
        }
        pos += count;
      }
    }
  }
  return g;
}

void SampleGrid::applyCut(const IntervalCache& cache, const GridBox* within) {
  // Branch-free (a cell holds millions of vertices): solid -> solid and was solid.
  static_assert(kSolid == 1, "the mask below takes kSolid as the lowest bit");
  for (auto& s : state_) s = static_cast<std::uint8_t>((s & kSolid) * (kSolid | kWasSolid));
  // Vertex states: the rule every cell applies (vertex_rule.h).
  GridBox reach = box_.intersect(cache.touched());
  if (within != nullptr) reach = reach.intersect(*within);
  if (!reach.empty())
    for (int y = reach.lo[1]; y <= reach.hi[1]; ++y)
      for (int x = reach.lo[0]; x <= reach.hi[0]; ++x) {
        const auto zLine = cache.line(2, x, y);
        if (zLine.empty()) continue;
        for (int z = reach.lo[2]; z <= reach.hi[2]; ++z) {
          std::uint8_t& s = state_[index(x, y, z)];
          if ((s & kSolid) && toolRemovesVertex(zLine, z)) s &= static_cast<std::uint8_t>(~kSolid);
        }
      }
  // Only vertices in the reach can have changed.
  if (!reach.empty())
    for (int z = reach.lo[2]; z <= reach.hi[2] && !changed_; ++z)
      for (int y = reach.lo[1]; y <= reach.hi[1]; ++y) {
        const std::size_t i0 = index(reach.lo[0], y, z);
        for (std::size_t i = i0; i <= i0 + (reach.hi[0] - reach.lo[0]); ++i)
          if (bool(state_[i] & kSolid) != bool(state_[i] & kWasSolid)) changed_ = true;
      }
  // Crossings, edge by edge in all three families (the same function every
  // cell holding an edge uses).
  for (int x = 0; x < 3; ++x) {
    const int xu = axisU(x), xv = axisV(x);
    const std::size_t sx = stride(x);
    // A line beside the reach: no vertex on it changed and the tool misses it here.
    if (reach.empty()) break;
    for (int cv = reach.lo[xv]; cv <= reach.hi[xv]; ++cv) {
      for (int cu = reach.lo[xu]; cu <= reach.hi[xu]; ++cu) {
        const auto tool = cache.line(x, cu, cv);
        const std::size_t i0 = index(vertex(x, box_.lo[x], cu, cv));
        for (int k = 0; k + 1 < n_[x]; ++k) {
          const std::size_t i = i0 + k * sx;
          const std::uint8_t s0 = state_[i], s1 = state_[i + sx];
          const bool n0 = s0 & kSolid, n1 = s1 & kSolid;
          const bool o0 = s0 & kWasSolid, o1 = s1 & kWasSolid;
          double& c = cross_[x][i];
          if (n0 == n1) {
            if (!std::isnan(c)) changed_ = true;
            c = kNaN;
            continue;
          }
          if (tool.empty() && o0 == n0 && o1 == n1) continue;
          const double nc = edgeCrossingAfterCut(o0, o1, c, n0, n1, box_.lo[x] + k, tool);
          if (!(nc == c)) changed_ = true;
          c = nc;
        }
      }
    }
  }
}

bool SampleGrid::columnValid(Direction d, int cu, int cv) const {
  const int a = d.axis, n = n_[a];
  const std::size_t st = stride(a);
  const std::size_t i0 = index(vertex(a, box_.lo[a], cu, cv));
  bool seenEmpty = false;
  for (int k = 0; k < n; ++k) {
    const int kk = d.sign > 0 ? k : n - 1 - k;
    const bool s = state_[i0 + kk * st] & kSolid;
    if (s && seenEmpty) return false;
    seenEmpty |= !s;
  }
  return true;
}

double SampleGrid::columnHeight(Direction d, int cu, int cv) const {
  const int a = d.axis, n = n_[a], lo = box_.lo[a], hi = box_.hi[a];
  const std::size_t st = stride(a);
  const std::size_t i0 = index(vertex(a, lo, cu, cv));
  int m = 0;  // solid vertices counted from the heightmap's base face
  while (m < n && (state_[i0 + (d.sign > 0 ? m : n - 1 - m) * st] & kSolid)) ++m;
  if (m == 0) return d.sign > 0 ? -kInf : kInf;
  if (m == n) return d.sign > 0 ? hi : lo;
  if (d.sign > 0) {
    const int k = lo + m - 1;  // last solid vertex; the crossing lies in [k, k+1)
    double c = cross_[a][i0 + (m - 1) * st];
    if (std::isnan(c)) c = k + 0.5;
    return std::clamp(c, double(k), std::nextafter(double(k + 1), -kInf));
  }
  const int k = hi - m + 1;  // lowest solid vertex; the crossing lies in (k-1, k]
  double c = cross_[a][i0 + (n - m - 1) * st];
  if (std::isnan(c)) c = k - 0.5;
  return std::clamp(c, std::nextafter(double(k - 1), kInf), double(k));
}

void appendEdgeCrossings(const SampleGrid& g, const ThreeMap& map, const ColumnStraddle& st, int x,
                         int edge, int y, int row, double h0, double h1, std::vector<double>& out) {
  for (int i = 0; i < st.total(); ++i) {
    std::array<int, 3> p{};
    p[map.axis()] = st.level(i);
    p[x] = edge;
    p[y] = row;
    double value = g.crossing(x, g.index(p));
    if (std::isnan(value)) value = map.interpolatedCrossing(h0, h1, edge, p[map.axis()]);
    out.push_back(value);
  }
}

bool SampleGrid::twoSidedColumn(Direction d, int cu, int cv, double& height, bool& flipped) const {
  flipped = !columnValid(d, cu, cv);
  if (flipped) {
    d.sign = -d.sign;
    if (!columnValid(d, cu, cv)) return false;
  }
  height = columnHeight(d, cu, cv);
  return true;
}

ThreeMap encodeMap(const SampleGrid& g, Direction d, bool threeWay, bool twoSided) {
  ThreeMap map(g.box(), d, threeWay);
  const int u = map.uAxis(), v = map.vAxis();
  const GridBox& box = g.box();
  map.reserveAllColumns();
  for (int cv = box.lo[v]; cv <= box.hi[v]; ++cv)
    for (int cu = box.lo[u]; cu <= box.hi[u]; ++cu) {
      double h = 0.0;
      bool flipped = false;
      if (twoSided && g.twoSidedColumn(d, cu, cv, h, flipped))
        map.setColumn(cu - box.lo[u], cv - box.lo[v], h, flipped);
      else
        map.setHeight(cu - box.lo[u], cv - box.lo[v], g.columnHeight(d, cu, cv));
    }
  map.releaseSlack();
  if (!threeWay) return map;
  for (int family = 0; family < 2; ++family) {
    const int x = family == 0 ? u : v, y = family == 0 ? v : u;
    for (int r = 0; r < map.rowCount(family); ++r) {
      std::vector<double>& dst = map.row(family, r);
      for (int e = 0; e < map.edgesInRow(family); ++e) {
        appendEdgeCrossings(g, map, map.straddleEdge(family, r, e), x, box.lo[x] + e, y,
                            box.lo[y] + r, map.rowHeight(family, r, e),
                            map.rowHeight(family, r, e + 1), dst);
      }
      dst.shrink_to_fit();
    }
  }
  return map;
}

}  // namespace mdhd::mdh

// Read-only questions to the stock: membership, intervals, volume, area, probes.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sim/mdh/interval_cache.h"
#include "sim/mdh/line_segments.h"
#include "sim/mdh/stock.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

namespace {

// Solid segments (grid units) of a partial cell along the grid line of `axis`
// through the vertex whose other two coordinates are given in `at`.
void partialSegments(const ThreeMap& m, int axis, const std::array<int, 3>& at,
                     std::vector<Span>& out) {
  const GridBox& box = m.box();
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  if (axis == a) {
    const int iu = at[u] - box.lo[u], iv = at[v] - box.lo[v];
    const double len = m.columnLengthAt(iu, iv);
    if (m.columnCount(iu, iv) == 0) return;
    if (m.columnUp(iu, iv))
      out.push_back({double(box.lo[a]), box.lo[a] + len});
    else
      out.push_back({box.hi[a] - len, double(box.hi[a])});
    return;
  }
  const int family = axis == u ? 0 : 1;
  const int other = family == 0 ? v : u;
  const int r = at[other] - box.lo[other];
  const int k = at[a];
  const int n = box.points(axis);
  // Scratch kept per thread: a query over every grid line of a region (the overhang
  // area) asks this once per line and cell.
  thread_local std::vector<int> counts;
  thread_local std::vector<std::uint8_t> solid, ups;
  thread_local std::vector<double> cross;
  thread_local std::vector<Span> segs;
  counts.resize(n);
  solid.resize(n);
  ups.resize(n);
  cross.assign(n - 1, std::nan(""));
  for (int e = 0; e < n; ++e) {
    const int iu = family == 0 ? e : r, iv = family == 0 ? r : e;
    counts[e] = m.columnCount(iu, iv);
    solid[e] = m.columnSolidAt(iu, iv, k);
    ups[e] = m.columnUp(iu, iv);
  }
  std::size_t pos = 0;
  for (int e = 0; e + 1 < n; ++e) {
    const ColumnStraddle st =
        columnsStraddle(counts[e], ups[e], counts[e + 1], ups[e + 1], box.lo[a], box.hi[a]);
    const int idx = st.indexOf(k);
    if (idx >= 0) {
      cross[e] = m.threeWay()
                     ? m.row(family, r)[pos + idx]
                     : m.interpolatedCrossing(m.rowHeight(family, r, e),
                                              m.rowHeight(family, r, e + 1), box.lo[axis] + e, k);
    }
    pos += st.total();
  }
  segs.clear();
  segmentsFromSamples(box.lo[axis], solid, cross, segs);
  out.insert(out.end(), segs.begin(), segs.end());
}

void leafSegments(const Cell& c, int axis, const std::array<int, 3>& at, std::vector<Span>& out) {
  if (c.state == CellState::kSolid)
    out.push_back({double(c.box.lo[axis]), double(c.box.hi[axis])});
  else if (c.state == CellState::kPartial)
    partialSegments(*c.map, axis, at, out);
}

void lineSegments(const Cell& c, int axis, const std::array<int, 3>& at, std::vector<Span>& out) {
  if (c.state != CellState::kInner) {
    leafSegments(c, axis, at, out);
    return;
  }
  if (c.splitAxis == axis) {
    lineSegments(*c.child[0], axis, at, out);
    lineSegments(*c.child[1], axis, at, out);
    return;
  }
  lineSegments(*c.child[at[c.splitAxis] < c.splitAt ? 0 : 1], axis, at, out);
}

}  // namespace

const Cell* Stock::leafAt(const glm::dvec3& g) const {
  std::array<int, 3> b{};
  for (int a = 0; a < 3; ++a)
    b[a] = std::clamp(static_cast<int>(std::floor(g[a] / brickSize_[a])), 0, bricks_[a] - 1);
  const Cell* c = &roots_[brickIndex(b)];
  while (c->state == CellState::kInner) c = c->child[g[c->splitAxis] < c->splitAt ? 0 : 1].get();
  return c;
}

namespace {

// A point of a square that a wall crosses between two rows of columns, the wall
// holding the map's axis (a 3-map keeps it in the crossings of the edges across the
// square, exactly on every grid line; bilinear parent heights would blur it over
// most of a grid spacing): its side of the wall at its level, from the crossings of
// the square's two edges of one family at the grid levels around it. Nothing when
// the square's columns do not make one such wall there.
std::optional<bool> wallSide(const ThreeMap& m, const glm::dvec3& g, int iu, int iv, double tu,
                             double tv) {
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  const GridBox& box = m.box();
  const int l0 = static_cast<int>(std::floor(g[a]));
  if (!m.threeWay() || l0 < box.lo[a] || l0 + 1 > box.hi[a]) return std::nullopt;
  const double ta = g[a] - l0;
  for (int f = 0; f < 2; ++f) {
    // f 0: the edges iu -> iu + 1 of rows iv and iv + 1; f 1: iv -> iv + 1 of rows iu, iu + 1.
    const int e = f == 0 ? iu : iv, r0 = f == 0 ? iv : iu;
    bool side = false;  // the edges' first column solid (the wall's solid side)
    double at[2];
    bool wall = true;
    for (int j = 0; j < 2 && wall; ++j) {
      const int r = r0 + j;
      const auto solid = [&](int k) {
        return f == 0 ? m.columnSolidAt(e, r, k) : m.columnSolidAt(r, e, k);
      };
      const bool s = solid(l0);
      const double x0 = m.edgeCrossing(f, r, e, l0), x1 = m.edgeCrossing(f, r, e, l0 + 1);
      wall = s == solid(l0 + 1) && (j == 0 || s == side) && !std::isnan(x0) && !std::isnan(x1);
      side = s;
      at[j] = x0 + ta * (x1 - x0);
    }
    if (!wall) continue;
    const double across = f == 0 ? tv : tu, along = f == 0 ? g[u] : g[v];
    return (along <= at[0] + across * (at[1] - at[0])) == side;
  }
  return std::nullopt;
}

}  // namespace

bool Stock::isSolid(const glm::dvec3& p) const {
  ensureSettled();  // a z map's crossings may be pending (lazy_crossings.h)
  glm::dvec3 g;
  for (int a = 0; a < 3; ++a) {
    g[a] = grid_.toGrid(a, p[a]);
    if (!(g[a] >= 0.0 && g[a] <= grid_.cubes[a])) return false;
  }
  const Cell* c = leafAt(g);
  if (c->state != CellState::kPartial) return c->state == CellState::kSolid;
  // Bilinear depth into the solid between the four columns around the point (for
  // columns all on one side: the bilinear height compared with the point's).
  const ThreeMap& m = *c->map;
  const GridBox& box = m.box();
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  const double fu = std::clamp(g[u] - box.lo[u], 0.0, double(box.cubes(u)));
  const double fv = std::clamp(g[v] - box.lo[v], 0.0, double(box.cubes(v)));
  const int iu = std::min(static_cast<int>(fu), box.cubes(u) - 1);
  const int iv = std::min(static_cast<int>(fv), box.cubes(v) - 1);
  const double tu = fu - iu, tv = fv - iv;
  if (const std::optional<bool> side = wallSide(m, g, iu, iv, tu, tv)) return *side;
  const double below = box.lo[a] - 1.0, above = box.hi[a] + 1.0;
  auto depth = [&](int du, int dv) {
    const double x = std::clamp(m.height(iu + du, iv + dv), below, above);
    return m.columnUp(iu + du, iv + dv) ? x - g[a] : g[a] - x;
  };
  return (1 - tu) * (1 - tv) * depth(0, 0) + tu * (1 - tv) * depth(1, 0) +
             (1 - tu) * tv * depth(0, 1) + tu * tv * depth(1, 1) >=
         0.0;
}

void Stock::solidIntervals(int axis, int iu, int iv, std::vector<geom::Interval>& out) const {
  out.clear();
  // Pending cuts (lazy_crossings.h) are only ever in z maps, whose z lines are their heights.
  if (axis != 2) ensureSettled();
  const int u = axisU(axis), v = axisV(axis);
  if (axis < 0 || axis > 2 || iu < 0 || iu > grid_.cubes[u] || iv < 0 || iv > grid_.cubes[v])
    throw std::out_of_range("mdh: grid line (" + std::to_string(axis) + ", " + std::to_string(iu) +
                            ", " + std::to_string(iv) + ") is outside the stock");
  std::vector<Span> segs;
  gridLineSegments(axis, iu, iv, segs);
  for (const Span& s : segs) {
    out.push_back({grid_.toMm(axis, s.lo), grid_.toMm(axis, s.hi)});
  }
}

void Stock::onBrickBands(const std::function<void(std::size_t)>& work) const {
  const std::size_t n = roots_.size();
  const auto band = [&](std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) work(b);
  };
  const std::size_t parts = std::clamp<std::size_t>(threads_, 1, std::max<std::size_t>(1, n / 8));
  std::vector<std::jthread> helpers;
  for (std::size_t k = 1; k < parts; ++k)
    helpers.emplace_back(band, k * n / parts, (k + 1) * n / parts);
  band(0, n / parts);
}

double Stock::volume() const {
  ensureSettled();
  // Brick by brick (grid units), the bricks added in their order: the same bits on
  // any number of threads. Summing a 3-way map's edge profiles is the work (the
  // final volume of the dome at density 10: 0.36 G instructions).
  std::vector<double> perBrick(roots_.size(), 0.0);
  onBrickBands([&](std::size_t b) {
    visitLeaves(roots_[b], [&](const LeafView& leaf) {
      if (leaf.state == CellState::kSolid)
        perBrick[b] += double(leaf.box.cubes(0)) * leaf.box.cubes(1) * leaf.box.cubes(2);
      else if (leaf.map)
        perBrick[b] += leaf.map->volume();
    });
  });
  double v = 0.0;
  for (const double b : perBrick) v += b;
  return v * grid_.h * grid_.h * grid_.h;
}

void Stock::gridLineSegments(int axis, int iu, int iv, std::vector<Span>& out) const {
  out.clear();
  const int u = axisU(axis), v = axisV(axis);
  std::array<int, 3> at{};
  at[u] = iu;
  at[v] = iv;
  std::array<int, 3> b{};
  b[u] = std::min(iu / brickSize_[u], bricks_[u] - 1);
  b[v] = std::min(iv / brickSize_[v], bricks_[v] - 1);
  std::vector<Span> segs;
  for (b[axis] = 0; b[axis] < bricks_[axis]; ++b[axis])
    lineSegments(roots_[brickIndex(b)], axis, at, segs);
  for (const Span& s : segs) {
    if (!out.empty() && s.lo <= out.back().hi + 1e-9)
      out.back().hi = std::max(out.back().hi, s.hi);
    else
      out.push_back(s);
  }
}

SurfaceArea Stock::area() const {
  ensureSettled();
  // Projected areas from the crossings of every grid line: each crossing of
  // an a line stands for h^2 of surface projected along a, signed by which
  // side is solid. Uses all three families of samples, and is exact for
  // faces on grid planes whatever the cells' directions.
  SurfaceArea out;
  const double h2 = grid_.h * grid_.h;
  std::vector<Span> segs;
  for (int a = 0; a < 3; ++a) {
    const int u = axisU(a), v = axisV(a), n = grid_.cubes[a];
    for (int iv = 0; iv <= grid_.cubes[v]; ++iv)
      for (int iu = 0; iu <= grid_.cubes[u]; ++iu) {
        const double w = (iu == 0 || iu == grid_.cubes[u] ? 0.5 : 1.0) *
                         (iv == 0 || iv == grid_.cubes[v] ? 0.5 : 1.0) * h2;
        gridLineSegments(a, iu, iv, segs);
        for (const Span& s : segs) {
          if (s.lo > 1e-9) out.by_direction[2 * a + 1] += w;  // solid above: faces -a
          if (s.hi < n - 1e-9) out.by_direction[2 * a] += w;
        }
      }
  }
  out.overhang = out.by_direction[5];
  for (double x : out.by_direction) out.total += x;
  return out;
}

Overlap Stock::probe(const geom::LineSolid& solid, double tolerance) const {
  Overlap out;
  const IntervalCache cache(grid_, solid, nullptr, 1u << 2);  // z lines only
  const GridBox& t = cache.touched();
  if (t.empty()) return out;
  const double h = grid_.h;
  std::vector<Span> segs;
  for (int iy = t.lo[1]; iy <= t.hi[1]; ++iy)
    for (int ix = t.lo[0]; ix <= t.hi[0]; ++ix) {
      const auto tool = cache.line(2, ix, iy);
      if (tool.empty()) continue;
      gridLineSegments(2, ix, iy, segs);
      double len = 0.0;
      for (const Span& s : segs)
        for (const Span& x : tool)
          len += std::max(0.0, std::min(s.hi, x.hi) - std::max(s.lo, x.lo));
      const double w = (ix == 0 || ix == grid_.cubes[0] ? 0.5 : 1.0) *
                       (iy == 0 || iy == grid_.cubes[1] ? 0.5 : 1.0);
      out.volume += w * len * h * h * h;
      out.max_length = std::max(out.max_length, len * h);
    }
  out.touched = out.max_length > tolerance;
  return out;
}

bool Stock::removesMaterial(const geom::LineSolid& solid, const geom::FreshRegion* region,
                            std::span<const geom::LineSolid* const> cutBefore,
                            const glm::dvec3& first, glm::dvec3* hit) const {
  geom::Aabb box = solid.bounds();
  if (region != nullptr) box = region->clip(box);
  if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y && box.lo.z <= box.hi.z)) return false;
  int lo[2], hi[2];
  for (int a = 0; a < 2; ++a) {
    lo[a] = static_cast<int>(
        std::clamp(std::ceil(grid_.toGrid(a, box.lo[a])), 0.0, double(grid_.cubes[a]) + 1.0));
    hi[a] = static_cast<int>(
        std::clamp(std::floor(grid_.toGrid(a, box.hi[a])), -1.0, double(grid_.cubes[a])));
  }
  std::vector<geom::Interval> mm;
  std::vector<Span> tool, other, left, segs;
  const auto along = [&](const geom::LineSolid& s, double x, double y, std::vector<Span>& out) {
    mm.clear();
    s.lineIntervals(2, x, y, mm);
    out.clear();
    for (const geom::Interval& i : mm)
      out.push_back({grid_.toGrid(2, i.lo), grid_.toGrid(2, i.hi)});
  };
  // Cheapest test first: the tool's intervals, the stock's, then the pending cuts'.
  const auto removes = [&](int ix, int iy) {
    const double x = grid_.toMm(0, ix), y = grid_.toMm(1, iy);
    along(solid, x, y, tool);
    if (tool.empty()) return false;
    gridLineSegments(2, ix, iy, segs);
    left.clear();
    for (const Span& s : segs)
      for (const Span& t : tool) {
        const Span both{std::max(s.lo, t.lo), std::min(s.hi, t.hi)};
        if (both.hi - both.lo > kToolSlack) left.push_back(both);
      }
    tool.swap(left);
    for (const geom::LineSolid* before : cutBefore) {
      if (tool.empty()) return false;
      along(*before, x, y, other);
      if (other.empty()) continue;
      subtractOpen(tool, other, left);
      tool.swap(left);
    }
    for (const Span& t : tool)
      if (t.hi - t.lo > kToolSlack) {
        if (hit != nullptr) *hit = {x, y, grid_.toMm(2, 0.5 * (t.lo + t.hi))};
        return true;
      }
    return false;
  };
  // Outwards from `first`, rows nearest it first and each row from its column out:
  // a raster step's removal lies ahead of its tip, on its row or column.
  const auto outwards = [](int centre, int from, int to, int k) {
    const int c = std::clamp(centre, from, to);
    // 0, +1, -1, +2, -2, ... skipping what falls outside [from, to].
    const int below = c - from, above = to - c, pairs = std::min(below, above);
    if (k <= 2 * pairs) return k == 0 ? c : (k % 2 == 1 ? c + (k + 1) / 2 : c - k / 2);
    const int rest = k - 2 * pairs;
    return above > below ? c + pairs + rest : c - pairs - rest;
  };
  const int fx = static_cast<int>(std::lround(grid_.toGrid(0, first.x)));
  const int fy = static_cast<int>(std::lround(grid_.toGrid(1, first.y)));
  for (int ky = 0; ky <= hi[1] - lo[1]; ++ky) {
    const int iy = outwards(fy, lo[1], hi[1], ky);
    for (int kx = 0; kx <= hi[0] - lo[0]; ++kx)
      if (removes(outwards(fx, lo[0], hi[0], kx), iy)) return true;
  }
  return false;
}

void Stock::forEachLeaf(const std::function<void(const LeafView&)>& f) const {
  ensureSettled();
  for (const Cell& root : roots_) visitLeaves(root, f);
}

}  // namespace mdhd::mdh

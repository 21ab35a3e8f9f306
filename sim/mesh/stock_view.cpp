// The adapter: everything the mesher reads from sim/mdh goes through here.
#include "sim/mesh/stock_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sim/mdh/stock.h"

namespace mdhd::mesh {

namespace {

constexpr std::int64_t kMaxBuckets = std::int64_t{1} << 20;

}  // namespace

StockView::StockView(const mdh::Stock& stock, int threads) {
  const mdh::GridSpec& g = stock.grid();
  origin_ = g.origin;
  spacing_ = g.h;
  cubes_ = g.cubes;
  stock.forEachLeaf([&](const mdh::LeafView& lv) {
    Leaf leaf;
    leaf.info.lo = lv.box.lo;
    leaf.info.hi = lv.box.hi;
    if (lv.state == mdh::CellState::kPartial && lv.map != nullptr) {
      leaf.info.kind = LeafKind::kPartial;
      leaf.info.axis = lv.map->axis();
      leaf.info.sign = lv.map->direction().sign;
      leaf.info.twoSided = lv.map->hasFlips();
      leaf.map = lv.map;
    } else {
      leaf.info.kind = lv.state == mdh::CellState::kEmpty ? LeafKind::kEmpty : LeafKind::kSolid;
    }
    leaves_.push_back(std::move(leaf));
  });
  // The rows' offsets, leaf by leaf: a fifth of a fine mesh's time on one thread.
  const auto index = [&](int first, int step) {
    for (int i = first; i < leafCount(); i += step) {
      Leaf& leaf = leaves_[static_cast<std::size_t>(i)];
      if (leaf.map != nullptr && leaf.map->threeWay()) indexRows(leaf);
    }
  };
  std::vector<std::thread> helpers;
  const int workers = std::clamp(threads, 1, 64);
  for (int t = 1; t < workers; ++t) helpers.emplace_back(index, t, workers);
  index(0, workers);
  for (std::thread& t : helpers) t.join();
  for (const Leaf& leaf : leaves_) brokenLeaves_ += leaf.rowsBroken ? 1 : 0;
  auto bucketCount = [&] {
    std::int64_t n = 1;
    for (int a = 0; a < 3; ++a) n *= cubes_[a] / bucketSize_ + 1;
    return n;
  };
  while (bucketCount() > kMaxBuckets) bucketSize_ *= 2;
  for (int a = 0; a < 3; ++a) buckets_[a] = cubes_[a] / bucketSize_ + 1;
  // Flat lists (offsets into one array): a vector per bucket cost a million
  // allocations on a fine stock.
  const auto forEachBucket = [&](int i, auto&& f) {
    GridPoint b0{}, b1{};
    for (int a = 0; a < 3; ++a) {
      const LeafInfo& l = leaves_[i].info;
      const int top = l.hi[a] == cubes_[a] ? l.hi[a] : l.hi[a] - 1;  // last owned coordinate
      b0[a] = l.lo[a] / bucketSize_;
      b1[a] = top / bucketSize_;
    }
    for (int z = b0[2]; z <= b1[2]; ++z)
      for (int y = b0[1]; y <= b1[1]; ++y)
        for (int x = b0[0]; x <= b1[0]; ++x) f(x + buckets_[0] * (y + buckets_[1] * z));
  };
  bucketStart_.assign(static_cast<std::size_t>(bucketCount()) + 1, 0);
  for (int i = 0; i < leafCount(); ++i) forEachBucket(i, [&](int b) { ++bucketStart_[b + 1]; });
  for (std::size_t b = 1; b < bucketStart_.size(); ++b) bucketStart_[b] += bucketStart_[b - 1];
  bucketLeaves_.resize(bucketStart_.back());
  std::vector<std::uint32_t> next(bucketStart_.begin(), bucketStart_.end() - 1);
  for (int i = 0; i < leafCount(); ++i)
    forEachBucket(i, [&](int b) { bucketLeaves_[next[b]++] = i; });
}

StockView::~StockView() = default;

void StockView::indexRows(Leaf& leaf) {
  const mdh::ThreeMap& m = *leaf.map;
  // Each column's solid count once (a straddle from two heights counts both again).
  thread_local std::vector<int> counts;
  counts.resize(static_cast<std::size_t>(m.columnsU()) * m.columnsV());
  for (int iv = 0; iv < m.columnsV(); ++iv)
    for (int iu = 0; iu < m.columnsU(); ++iu)
      counts[static_cast<std::size_t>(iv) * m.columnsU() + iu] = m.columnCount(iu, iv);
  const auto countAt = [&](int f, int r, int e) {
    return f == 0 ? counts[static_cast<std::size_t>(r) * m.columnsU() + e]
                  : counts[static_cast<std::size_t>(e) * m.columnsU() + r];
  };
  const int lo = m.box().lo[m.axis()], hi = m.box().hi[m.axis()];
  const auto upAt = [&](int f, int r, int e) {
    return f == 0 ? m.columnUp(e, r) : m.columnUp(r, e);
  };
  for (int f = 0; f < 2; ++f) {
    const int edges = m.edgesInRow(f);
    leaf.rowStart[f].assign(static_cast<std::size_t>(m.rowCount(f)) * (edges + 1), 0);
    for (int r = 0; r < m.rowCount(f); ++r) {
      int pos = 0;
      int* start = &leaf.rowStart[f][static_cast<std::size_t>(r) * (edges + 1)];
      for (int e = 0; e < edges; ++e) {
        start[e] = pos;
        pos += mdh::columnsStraddle(countAt(f, r, e), upAt(f, r, e), countAt(f, r, e + 1),
                                    upAt(f, r, e + 1), lo, hi)
                   .total();
      }
      start[edges] = pos;
      if (static_cast<std::size_t>(pos) != m.row(f, r).size()) {
        // The engine broke its packing rule: do not index past the row;
        // this leaf's crossings are interpolated instead.
        leaf.rowStart[0].clear();
        leaf.rowStart[1].clear();
        leaf.rowsBroken = true;
        return;
      }
    }
  }
}

int StockView::bucketOf(const GridPoint& p) const {
  GridPoint b{};
  for (int a = 0; a < 3; ++a) b[a] = p[a] / bucketSize_;
  return b[0] + buckets_[0] * (b[1] + buckets_[1] * b[2]);
}

bool StockView::owns(int leaf, const GridPoint& p) const {
  const LeafInfo& l = leaves_[leaf].info;
  for (int a = 0; a < 3; ++a) {
    if (p[a] < l.lo[a]) return false;
    if (p[a] >= l.hi[a] && !(p[a] == l.hi[a] && l.hi[a] == cubes_[a])) return false;
  }
  return true;
}

int StockView::ownerOf(const GridPoint& p, int hint) const {
  if (hint >= 0 && owns(hint, p)) return hint;
  for (int a = 0; a < 3; ++a)
    if (p[a] < 0 || p[a] > cubes_[a])
      throw std::out_of_range("mesh: grid vertex (" + std::to_string(p[0]) + ", " +
                              std::to_string(p[1]) + ", " + std::to_string(p[2]) +
                              ") is outside the stock");
  const int b = bucketOf(p);
  for (std::uint32_t k = bucketStart_[b]; k < bucketStart_[b + 1]; ++k)
    if (owns(bucketLeaves_[k], p)) return bucketLeaves_[k];
  throw std::logic_error("mesh: no leaf holds grid vertex (" + std::to_string(p[0]) + ", " +
                         std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")");
}

bool StockView::solidIn(int leaf, const GridPoint& p) const {
  const Leaf& l = leaves_[leaf];
  if (l.info.kind != LeafKind::kPartial) return l.info.kind == LeafKind::kSolid;
  const mdh::ThreeMap& m = *l.map;
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  return m.columnSolidAt(p[u] - l.info.lo[u], p[v] - l.info.lo[v], p[a]);
}

int StockView::columnSolidCount(int leaf, int pu, int pv) const {
  const Leaf& l = leaves_[leaf];
  const mdh::ThreeMap& m = *l.map;
  return m.columnCount(pu - l.info.lo[m.uAxis()], pv - l.info.lo[m.vAxis()]);
}

double StockView::crossing(const GridPoint& p, int axis, int hint) const {
  return crossingOwnedBy(ownerOf(p, hint), p, axis);
}

double StockView::crossingOwnedBy(int owner, const GridPoint& p, int axis) const {
  const double x = crossingIn(owner, p, axis);
  if (!std::isnan(x)) return x;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  for (int d = 1; d < 4; ++d) {  // the cubes at -u, -v, -u-v beside the edge
    GridPoint c = p;
    c[u] -= d & 1;
    c[v] -= d >> 1;
    if (c[u] < 0 || c[v] < 0) continue;
    const int other = ownerOf(c, owner);
    if (other == owner) continue;
    const double y = crossingIn(other, p, axis);
    if (!std::isnan(y)) return y;
  }
  return x;
}

double StockView::columnSurface(int leaf, GridPoint p, double h) const {
  const LeafInfo& first = leaves_[leaf].info;
  const mdh::ThreeMap& m = *leaves_[leaf].map;
  const int a = first.axis, sign = first.sign, u = m.uAxis(), v = m.vAxis();
  const int n = m.solidCount(h);
  if (n > 0 && n < m.levels()) return h;  // callers mostly test this first
  const bool full = n > 0;
  // Full columns of a + map and empty ones of a - map have their surface above.
  const int dir = full == (sign > 0) ? 1 : -1;
  int at = leaf;
  // Bounded by the leaves stacked along the column; the guard only matters if
  // the tiling were ever inconsistent.
  for (int guard = 0; guard <= cubes_[a]; ++guard) {
    const LeafInfo& l = leaves_[at].info;
    if (dir < 0 ? l.lo[a] == 0 : l.hi[a] == cubes_[a]) return h;  // the stock's face
    const double plane = dir < 0 ? l.lo[a] : l.hi[a];
    p[a] = dir < 0 ? l.lo[a] - 1 : l.hi[a];
    at = ownerOf(p, at);
    const Leaf& next = leaves_[at];
    bool nextFull = next.info.kind == LeafKind::kSolid;
    if (next.info.kind == LeafKind::kPartial) {
      if (next.info.axis != a || next.info.sign != sign) return h;  // another surface
      const double g = next.map->height(p[u] - next.info.lo[u], p[v] - next.info.lo[v]);
      const int k = next.map->solidCount(g);
      if (k > 0 && k < next.map->levels()) return g;
      nextFull = k > 0;
    }
    // The column changes state on the plane between the two leaves: the surface is there.
    if (nextFull != full) return plane;
  }
  return h;
}

double StockView::crossingIn(int leaf, const GridPoint& p, int axis) const {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  const Leaf& l = leaves_[leaf];
  if (l.info.kind != LeafKind::kPartial) return kNone;
  const mdh::ThreeMap& m = *l.map;
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  const GridPoint& lo = l.info.lo;
  if (p[axis] >= l.info.hi[axis]) return kNone;  // the edge leaves the cell
  if (axis == a) {
    const int iu = p[u] - lo[u], iv = p[v] - lo[v];
    return m.columnSolidAt(iu, iv, p[a]) != m.columnSolidAt(iu, iv, p[a] + 1) ? m.height(iu, iv)
                                                                              : kNone;
  }
  const int f = axis == u ? 0 : 1;
  const int r = f == 0 ? p[v] - lo[v] : p[u] - lo[u];
  const int e = p[axis] - lo[axis];
  const double h0 = m.rowHeight(f, r, e), h1 = m.rowHeight(f, r, e + 1);
  const mdh::ColumnStraddle st = m.straddleEdge(f, r, e);
  const int k = p[a];
  const int at = st.indexOf(k);
  if (at < 0) return kNone;
  // A two-sided leaf's surface does not continue into the leaves along its axis.
  if (l.info.twoSided && l.rowsBroken) return m.interpolatedCrossing(h0, h1, p[axis], k);
  if (!m.threeWay() || l.rowsBroken) {
    // Most columns hold their surface in this leaf: the walk only for those that do not.
    const auto inside = [&](double h) {
      const int n = m.solidCount(h);
      return n != 0 && n != m.levels();
    };
    GridPoint c1 = p;
    c1[axis] += 1;
    return m.interpolatedCrossing(inside(h0) ? h0 : columnSurface(leaf, p, h0),
                                  inside(h1) ? h1 : columnSurface(leaf, c1, h1), p[axis], k);
  }
  const int edges = m.edgesInRow(f);
  const int start = l.rowStart[f][static_cast<std::size_t>(r) * (edges + 1) + e];
  return m.row(f, r)[static_cast<std::size_t>(start + at)];
}

}  // namespace mdhd::mesh

#include "sim/mdh/lazy_crossings.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sim/mdh/interval_cache.h"
#include "sim/mdh/line_segments.h"

namespace mdhd::mdh {

namespace {

constexpr std::uint64_t kQuietNaN = 0x7ff8000000000000ull;

std::uint32_t generationOf(double tagged) {
  return static_cast<std::uint32_t>(std::bit_cast<std::uint64_t>(tagged));
}

// One level whose crossing a resolve computes: row r, edge e, level k, index i in the
// row, and from which of the ring's cuts on (their index) it still has to be cut.
struct Item {
  int r, e, k;
  std::size_t i;
  int from;
};

// The pending cuts as a resolve uses them: each one's reach in the map and line cache.
struct Ring {
  explicit Ring(const ThreeMap& map) : m(map) {}
  const ThreeMap& m;
  int count = 0;
  std::uint32_t first = 0;  // the oldest's generation
  GridBox region[PendingCuts::kMax]{};
  GridBox any{};  // the smallest box holding every region
  // Whether cut j reached edge e (an end in its reach) of row r at level k.
  bool reached(int j, int x, int y, int r, int e, int k) const {
    const GridBox& g = region[j];
    const GridBox& box = m.box();
    const int ex = box.lo[x] + e, ry = box.lo[y] + r, a = m.axis();
    return ry >= g.lo[y] && ry <= g.hi[y] && ex + 1 >= g.lo[x] && ex <= g.hi[x] && k >= g.lo[a] &&
           k <= g.hi[a];
  }
};

// The items of one family: every straddled level that the coming cut keeps
// (`after`, if given) and that is due: a number the newest cut reached, or a NaN
// of a generation below `resolveBelow`.
void collect(const Ring& ring, const int* counts, const int* after, int family,
             std::uint32_t resolveBelow, std::vector<Item>& items) {
  const ThreeMap& m = ring.m;
  const GridBox& box = m.box();
  const int u = m.uAxis(), v = m.vAxis(), nu = m.columnsU();
  const int x = family == 0 ? u : v, y = family == 0 ? v : u;
  const auto at = [&](int r, int e) {
    return family == 0 ? static_cast<std::size_t>(r) * nu + e
                       : static_cast<std::size_t>(e) * nu + r;
  };
  // Only rows and edges with an end in some cut's reach can hold any: the cuts changed
  // columns there only, and reached no crossing elsewhere.
  const int r0 = std::max(0, ring.any.lo[y] - box.lo[y]);
  const int r1 = std::min(m.rowCount(family) - 1, ring.any.hi[y] - box.lo[y]);
  const int eFirst = std::max(0, ring.any.lo[x] - 1 - box.lo[x]);
  const int eEnd = std::min(m.edgesInRow(family), ring.any.hi[x] + 1 - box.lo[x]);
  const int newest = ring.count - 1;
  for (int r = r0; r <= r1; ++r) {
    const std::vector<double>& row = m.row(family, r);
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
      const int lo = std::max(first, keepFirst),
                hi = std::min(first + count, keepFirst + keepCount);
      for (int k = lo; k < hi; ++k) {
        const std::size_t i = pos + static_cast<std::size_t>(k - first);
        const double c = row[i];
        if (std::isnan(c)) {
          const std::uint32_t g = generationOf(c);
          if (g >= resolveBelow) continue;
          if (g < ring.first || g - ring.first >= static_cast<std::uint32_t>(ring.count))
            throw std::logic_error("mdh: a crossing is pending for a cut the cell no longer holds");
          items.push_back({r, e, k, i, static_cast<int>(g - ring.first)});
        } else if (ring.reached(newest, x, y, r, e, k)) {
          items.push_back({r, e, k, i, newest});
        }
      }
      pos += static_cast<std::size_t>(count);
    }
  }
}

// Computes the due crossings of `map` (see collect) through the cuts they wait for.
// `now`: the columns' solid counts (computed here when null).
void resolve(ThreeMap& map, const PendingCuts& pending, const GridSpec& grid, const int* now,
             const int* after, std::uint32_t resolveBelow) {
  if (pending.count == 0 || !map.threeWay()) return;
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  const GridBox& box = map.box();
  Ring ring(map);
  ring.count = pending.count;
  ring.first = pending.cuts[0].generation;
  ring.any = GridBox{};
  for (int j = 0; j < ring.count; ++j) {
    ring.region[j] = box.intersect(pending.cuts[j].reach);
    for (int ax = 0; ax < 3; ++ax) {
      ring.any.lo[ax] =
          j == 0 ? ring.region[j].lo[ax] : std::min(ring.any.lo[ax], ring.region[j].lo[ax]);
      ring.any.hi[ax] =
          j == 0 ? ring.region[j].hi[ax] : std::max(ring.any.hi[ax], ring.region[j].hi[ax]);
    }
  }
  const bool up = map.direction().sign > 0;
  const std::size_t columns = static_cast<std::size_t>(map.columnsU()) * map.columnsV();
  const int levels = box.points(a);
  thread_local std::vector<int> counts;
  thread_local std::vector<Item> items[2];
  thread_local std::vector<std::uint32_t> marks;  // (row, level) -> stamp of the last ask
  thread_local std::uint32_t stamp = 0;
  thread_local std::vector<int> lineU, lineV;
  if (now == nullptr) {
    counts.resize(columns);
    map.solidCounts(counts.data());
    now = counts.data();
  }
  bool any = false;
  for (int family = 0; family < 2; ++family) {
    items[family].clear();
    collect(ring, now, after, family, resolveBelow, items[family]);
    any = any || !items[family].empty();
  }
  if (!any) return;
  // Cut by cut, oldest first (each item's cuts in their order), so that one line
  // cache (and one store per thread, reused: nothing allocated once it has grown) is
  // alive at a time.
  thread_local LineStore store;
  for (int j = 0; j < ring.count; ++j) {
    IntervalCache cache(grid, *pending.cuts[j].solid, &store, (1u << u) | (1u << v));
    cache.setShared(false);
    for (int family = 0; family < 2; ++family) {
      const int x = family == 0 ? u : v, y = family == 0 ? v : u;
      const bool levelIsU = axisU(x) == a;
      const auto applies = [&](const Item& it) {
        return it.from == j || (it.from < j && ring.reached(j, x, y, it.r, it.e, it.k));
      };
      // The lines the items will ask for, filled together where the solid answers
      // many lines for less than one by one (IntervalCache::fillLines): the same answers.
      if (cache.linesPay(x)) {
        const std::size_t cells = static_cast<std::size_t>(map.rowCount(family)) * levels;
        if (marks.size() < cells) marks.assign(cells, 0), stamp = 0;
        if (++stamp == 0) std::fill(marks.begin(), marks.end(), 0), stamp = 1;
        lineU.clear();
        lineV.clear();
        for (const Item& it : items[family]) {
          if (!applies(it)) continue;
          std::uint32_t& mark = marks[static_cast<std::size_t>(it.r) * levels + (it.k - box.lo[a])];
          if (mark == stamp) continue;
          mark = stamp;
          const int fixed = box.lo[y] + it.r;
          lineU.push_back(levelIsU ? it.k : fixed);
          lineV.push_back(levelIsU ? fixed : it.k);
        }
        if (lineU.size() > 1) cache.fillLines(x, lineU, lineV);
      }
      // Up a wall the levels of a solid's prism band share one line: the same question
      // is answered once (as fast_cut.cpp's edgeCrossings does).
      const Span* lastTool = nullptr;
      std::size_t lastSize = 0;
      double lastOld = 0.0, lastValue = 0.0;
      unsigned lastStates = ~0u;
      int lastRow = -1, lastEdge = -1;
      for (const Item& it : items[family]) {
        if (!applies(it)) continue;
        double& c = map.row(family, it.r)[it.i];
        const bool fresh = it.from == j && std::isnan(c);
        const int fixed = box.lo[y] + it.r;
        const auto tool = levelIsU ? cache.line(x, it.k, fixed) : cache.line(x, fixed, it.k);
        if (!fresh && tool.empty()) continue;  // an edge the solid misses keeps its crossing
        const double h0 = map.rowHeight(family, it.r, it.e);
        const double h1 = map.rowHeight(family, it.r, it.e + 1);
        const bool n0 = up ? it.k <= h0 : it.k >= h0, n1 = up ? it.k <= h1 : it.k >= h1;
        const bool o0 = fresh || n0, o1 = fresh || n1;
        const unsigned states = o0 | o1 << 1 | n0 << 2 | n1 << 3;
        const bool sameOld = c == lastOld || (fresh && std::isnan(lastOld));
        if (!(it.e == lastEdge && it.r == lastRow && tool.data() == lastTool &&
              tool.size() == lastSize && sameOld && states == lastStates)) {
          lastValue = edgeCrossingAfterCut(o0, o1, c, n0, n1, box.lo[x] + it.e, tool);
          lastTool = tool.data(), lastSize = tool.size(), lastOld = c, lastStates = states;
          lastRow = it.r, lastEdge = it.e;
        }
        c = lastValue;
      }
    }
  }
}

}  // namespace

double pendingCrossing(std::uint32_t generation) {
  return std::bit_cast<double>(kQuietNaN | generation);
}

void advanceCrossings(ThreeMap& map, PendingCuts& pending, const GridSpec& grid,
                      const int* countsNow, const int* countsAfter) {
  if (pending.count == 0) return;
  const bool full = pending.count == PendingCuts::kMax;
  resolve(map, pending, grid, countsNow, countsAfter, full ? pending.cuts[0].generation + 1 : 0);
  if (!full) return;
  std::rotate(pending.cuts.begin(), pending.cuts.begin() + 1, pending.cuts.end());
  pending.cuts[PendingCuts::kMax - 1] = PendingCut{};
  --pending.count;
}

void settleCrossings(ThreeMap& map, PendingCuts& pending, const GridSpec& grid) {
  resolve(map, pending, grid, nullptr, nullptr, std::numeric_limits<std::uint32_t>::max());
  pending = PendingCuts{};
}

void relayoutCrossings(ThreeMap& map, const int* before, const int* after,
                       std::span<const std::size_t> moved, double fresh) {
  thread_local std::vector<double> mid;
  thread_local std::vector<int> lowest, highest;  // per row: its first and last moved column
  const int nu = map.columnsU();
  for (int family = 0; family < 2; ++family) {
    const auto at = [&](int r, int e) {
      return family == 0 ? static_cast<std::size_t>(r) * nu + e
                         : static_cast<std::size_t>(e) * nu + r;
    };
    const int rows = map.rowCount(family), edges = map.edgesInRow(family);
    lowest.assign(static_cast<std::size_t>(rows), edges + 1);
    highest.assign(static_cast<std::size_t>(rows), -1);
    for (std::size_t i : moved) {
      if (before[i] == after[i]) continue;
      const int r = static_cast<int>(family == 0 ? i / nu : i % nu);
      const int e = static_cast<int>(family == 0 ? i % nu : i / nu);
      lowest[r] = std::min(lowest[r], e);
      highest[r] = std::max(highest[r], e);
    }
    for (int r = 0; r < rows; ++r) {
      if (highest[r] < 0) continue;
      // Only the edges beside a moved column change their layout: the rows before and
      // after them keep their values, in one block each.
      const int e0 = std::max(0, lowest[r] - 1), e1 = std::min(edges, highest[r] + 1);
      std::vector<double>& src = map.row(family, r);
      std::size_t pos = 0;
      for (int e = 0; e < e0; ++e) {
        int of = 0, oc = 0;
        map.straddleCounts(before[at(r, e)], before[at(r, e + 1)], of, oc);
        pos += static_cast<std::size_t>(oc);
      }
      const std::size_t head = pos;
      mid.clear();
      for (int e = e0; e < e1; ++e) {
        int of = 0, oc = 0, nf = 0, nc = 0;
        map.straddleCounts(before[at(r, e)], before[at(r, e + 1)], of, oc);
        map.straddleCounts(after[at(r, e)], after[at(r, e + 1)], nf, nc);
        for (int k = nf; k < nf + nc; ++k)
          mid.push_back(k >= of && k < of + oc ? src[pos + (k - of)] : fresh);
        pos += static_cast<std::size_t>(oc);
      }
      const std::size_t tail = src.size() - pos, size = head + mid.size() + tail;
      // Reuse the row's storage unless it is too small or far too large (memory is
      // counted by capacity), as fast_cut.cpp's rebuildRow does.
      if (size > src.capacity() || src.capacity() > size + size / 4 + 4) {
        std::vector<double> row;
        row.reserve(size);
        row.insert(row.end(), src.begin(), src.begin() + static_cast<std::ptrdiff_t>(head));
        row.insert(row.end(), mid.begin(), mid.end());
        row.insert(row.end(), src.begin() + static_cast<std::ptrdiff_t>(pos), src.end());
        src = std::move(row);
      } else if (mid.size() == pos - head) {
        std::copy(mid.begin(), mid.end(), src.begin() + static_cast<std::ptrdiff_t>(head));
      } else {
        src.erase(src.begin() + static_cast<std::ptrdiff_t>(head),
                  src.begin() + static_cast<std::ptrdiff_t>(pos));
        src.insert(src.begin() + static_cast<std::ptrdiff_t>(head), mid.begin(), mid.end());
      }
    }
  }
}

void settlePending(Cell& cell, const GridSpec& grid) {
  if (!cell.pending) return;
  if (cell.map) settleCrossings(*cell.map, *cell.pending, grid);
  cell.pending.reset();
}

}  // namespace mdhd::mdh

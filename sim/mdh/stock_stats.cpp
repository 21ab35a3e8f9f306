// The stock's statistics and memory accounting (thesis 6.3).
#include <unordered_set>

#include "sim/mdh/stock.h"

namespace mdhd::mdh {

namespace {

std::uint64_t vertexKey(const std::array<int, 3>& p) {
  return (std::uint64_t(p[0]) << 42) | (std::uint64_t(p[1]) << 21) | std::uint64_t(p[2]);
}

// Grid points owning at least one surface sample on one of their three
// outgoing edges: the points a 3D pointer grid would point from.
std::int64_t sampleOwners(const ThreeMap& m, std::int64_t& parents, std::int64_t& embedded) {
  std::unordered_set<std::uint64_t> owners;
  const GridBox& box = m.box();
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  for (int iv = 0; iv < m.columnsV(); ++iv)
    for (int iu = 0; iu < m.columnsU(); ++iu) {
      const double h = m.height(iu, iv);
      const int n = m.solidCount(h);
      if (n == 0 || n == m.levels()) continue;
      ++parents;
      std::array<int, 3> p{};
      p[a] = m.direction().sign > 0 ? box.lo[a] + n - 1 : box.hi[a] - n;
      p[u] = box.lo[u] + iu;
      p[v] = box.lo[v] + iv;
      owners.insert(vertexKey(p));
    }
  if (!m.threeWay()) return static_cast<std::int64_t>(owners.size());
  for (int family = 0; family < 2; ++family) {
    const int x = family == 0 ? u : v, y = family == 0 ? v : u;
    for (int r = 0; r < m.rowCount(family); ++r)
      for (int e = 0; e < m.edgesInRow(family); ++e) {
        int first = 0, count = 0;
        m.straddle(m.rowHeight(family, r, e), m.rowHeight(family, r, e + 1), first, count);
        embedded += count;
        for (int i = 0; i < count; ++i) {
          std::array<int, 3> p{};
          p[a] = first + i;
          p[x] = box.lo[x] + e;
          p[y] = box.lo[y] + r;
          owners.insert(vertexKey(p));
        }
      }
  }
  return static_cast<std::int64_t>(owners.size());
}

std::int64_t countNodes(const Cell& c, std::size_t& bytes) {
  if (c.state != CellState::kInner) return 1;
  bytes += 2 * sizeof(Cell);
  return 1 + countNodes(*c.child[0], bytes) + countNodes(*c.child[1], bytes);
}

}  // namespace

Stats Stock::stats() const {
  Stats s;
  s.memoryBytes =
      sizeof(Stock) + roots_.capacity() * sizeof(Cell) + options_.ruleset.capacity() * sizeof(Rule);
  for (const Cell& root : roots_) s.cells += countNodes(root, s.memoryBytes);
  std::int64_t owners = 0;
  forEachLeaf([&](const LeafView& leaf) {
    ++s.leaves;
    if (leaf.state == CellState::kSolid)
      ++s.solid;
    else if (leaf.state == CellState::kEmpty)
      ++s.empty;
    if (!leaf.map) return;
    s.directions[leaf.map->direction().index()] += 1;
    s.memoryBytes += leaf.map->memoryBytes();
    owners += sampleOwners(*leaf.map, s.parentSamples, s.embeddedSamples);
  });
  s.splitsDirect = totals_.splits[int(SplitType::kDirect)];
  s.splitsIndirect = totals_.splits[int(SplitType::kIndirect)];
  s.splitsSignConflict = totals_.splits[int(SplitType::kSignConflict)];
  s.splitsFallback = totals_.splits[int(SplitType::kFallback)];
  s.overhangEvents = totals_.overhangEvents;
  s.resamples = totals_.resamples;
  s.forcedCells = totals_.forcedCells;
  s.forcedVertices = totals_.forcedVertices;
  // 3D pointer grid: an 8-byte pointer per grid point of the stock, plus a
  // triplet of height/normal samples (3 x (4-byte height + 3 x 4-byte normal))
  // per point that owns a surface sample.
  const double points =
      double(grid_.cubes[0] + 1) * double(grid_.cubes[1] + 1) * double(grid_.cubes[2] + 1);
  s.pointerGridBytes = 8.0 * points + 48.0 * double(owners);
  s.pointerGridPercent = 100.0 * double(s.memoryBytes) / s.pointerGridBytes;
  return s;
}

}  // namespace mdhd::mdh

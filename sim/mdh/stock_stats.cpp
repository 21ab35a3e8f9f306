// The stock's statistics and memory accounting (thesis 6.3).
#include <algorithm>
#include <array>
#include <vector>

#include "sim/mdh/stock.h"

namespace mdhd::mdh {

namespace {

// Grid points owning at least one surface sample on one of their three
// outgoing edges: the points a 3D pointer grid would point from. A column's own
// points are its parent sample's top solid vertex and the levels of the crossings on
// the two edges leaving it (each a run of levels): counted as the union of the two
// runs and the point, with no set.
std::int64_t sampleOwners(const ThreeMap& m, std::int64_t& parents, std::int64_t& embedded) {
  const GridBox& box = m.box();
  const int a = m.axis(), nu = m.columnsU(), nv = m.columnsV();
  std::int64_t owners = 0;
  for (int iv = 0; iv < nv; ++iv)
    for (int iu = 0; iu < nu; ++iu) {
      const double h = m.height(iu, iv);
      const int n = m.solidCount(h);
      const bool partial = n != 0 && n != m.levels();
      parents += partial;
      int first[2] = {0, 0}, count[2] = {0, 0};
      if (m.threeWay()) {
        if (iu + 1 < nu) m.straddle(h, m.height(iu + 1, iv), first[0], count[0]);
        if (iv + 1 < nv) m.straddle(h, m.height(iu, iv + 1), first[1], count[1]);
        embedded += count[0] + count[1];
      }
      const int overlap = std::max(
          0, std::min(first[0] + count[0], first[1] + count[1]) - std::max(first[0], first[1]));
      owners += count[0] + count[1] - overlap;
      if (!partial) continue;
      const int top = m.direction().sign > 0 ? box.lo[a] + n - 1 : box.hi[a] - n;
      const auto in = [&](int k) {
        return (k >= first[0] && k < first[0] + count[0]) ||
               (k >= first[1] && k < first[1] + count[1]);
      };
      owners += !in(top);
    }
  return owners;
}

std::int64_t countNodes(const Cell& c, std::size_t& bytes) {
  if (c.state != CellState::kInner) return 1;
  bytes += 2 * sizeof(Cell);
  return 1 + countNodes(*c.child[0], bytes) + countNodes(*c.child[1], bytes);
}

}  // namespace

Stats Stock::stats() const {
  ensureSettled();  // the rows' sizes are those of the settled maps
  Stats s;
  s.memoryBytes =
      sizeof(Stock) + roots_.capacity() * sizeof(Cell) + options_.ruleset.capacity() * sizeof(Rule);
  for (const Cell& root : roots_) s.cells += countNodes(root, s.memoryBytes);
  // Per brick on the stock's threads (integers: any order gives the same sums).
  struct Counts {
    std::int64_t leaves = 0, solid = 0, empty = 0, owners = 0, parents = 0, embedded = 0;
    std::size_t bytes = 0;
    std::array<std::int64_t, 6> directions{};
  };
  std::vector<Counts> perBrick(roots_.size());
  onBrickBands([&](std::size_t b) {
    Counts& c = perBrick[b];
    visitLeaves(roots_[b], [&](const LeafView& leaf) {
      ++c.leaves;
      if (leaf.state == CellState::kSolid)
        ++c.solid;
      else if (leaf.state == CellState::kEmpty)
        ++c.empty;
      if (!leaf.map) return;
      c.directions[leaf.map->direction().index()] += 1;
      c.bytes += leaf.map->memoryBytes();
      c.owners += sampleOwners(*leaf.map, c.parents, c.embedded);
    });
  });
  std::int64_t owners = 0;
  for (const Counts& c : perBrick) {
    s.leaves += c.leaves;
    s.solid += c.solid;
    s.empty += c.empty;
    for (int d = 0; d < 6; ++d) s.directions[d] += c.directions[d];
    s.memoryBytes += c.bytes;
    s.parentSamples += c.parents;
    s.embeddedSamples += c.embedded;
    owners += c.owners;
  }
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

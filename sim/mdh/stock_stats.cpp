// The stock's statistics and memory accounting (thesis 6.3).
#include <algorithm>
#include <array>
#include <limits>
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
      const int n = m.columnCount(iu, iv);
      const bool partial = n != 0 && n != m.levels();
      parents += partial;
      // The level runs of both edges' crossings (up to two each where a neighbour is on
      // the other side of a two-sided map) and the top solid vertex, as a union.
      std::array<std::pair<int, int>, 5> runs;  // [first, end)
      std::size_t count = 0;
      if (m.threeWay()) {
        for (int e = 0; e < 2; ++e) {
          if (e == 0 ? iu + 1 >= nu : iv + 1 >= nv) continue;
          const ColumnStraddle st = e == 0 ? m.straddleColumns(iu, iv, iu + 1, iv)
                                           : m.straddleColumns(iu, iv, iu, iv + 1);
          embedded += st.total();
          for (int r = 0; r < 2; ++r)
            if (st.count[r] > 0) runs[count++] = {st.first[r], st.first[r] + st.count[r]};
        }
      }
      if (partial) {
        const int top = m.columnUp(iu, iv) ? box.lo[a] + n - 1 : box.hi[a] - n;
        runs[count++] = {top, top + 1};
      }
      // At most five runs: an insertion sort.
      for (std::size_t i = 1; i < count; ++i)
        for (std::size_t j = i; j > 0 && runs[j] < runs[j - 1]; --j)
          std::swap(runs[j], runs[j - 1]);
      int reached = std::numeric_limits<int>::min();
      for (std::size_t i = 0; i < count; ++i) {
        const int from = std::max(runs[i].first, reached);
        if (runs[i].second > from) owners += runs[i].second - from;
        reached = std::max(reached, runs[i].second);
      }
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
    std::int64_t flipped = 0, twoSided = 0;
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
      c.flipped += leaf.map->flippedColumns();
      c.twoSided += leaf.map->hasFlips();
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
    s.flippedColumns += c.flipped;
    s.twoSidedLeaves += c.twoSided;
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

#include "sim/mdh/two_sided_cut.h"

#include <cmath>
#include <vector>

#include "sim/mdh/sample_grid.h"

namespace mdhd::mdh {

TwoSidedCut twoSidedCut(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                        double* volumeDelta) {
  const GridBox& box = map.box();
  const int a = map.axis(), u = map.uAxis(), v = map.vAxis();
  const GridBox hit = box.intersect(reach);
  if (hit.empty()) return TwoSidedCut::kUnchanged;
  // The reached columns and one more on each side (an edge from a reached column to
  // the next can move), over the map's whole height (a column's side depends on all
  // of it). Columns on the footprint's rim keep their states.
  GridBox sub = box;
  for (int x : {u, v}) {
    sub.lo[x] = std::max(box.lo[x], hit.lo[x] - 1);
    sub.hi[x] = std::min(box.hi[x], hit.hi[x] + 1);
  }
  SampleGrid g = SampleGrid::decode(map, sub);
  g.applyCut(cache, &reach);
  if (!g.changed()) return TwoSidedCut::kUnchanged;
  const Direction d = map.direction();
  const int iu0 = sub.lo[u] - box.lo[u], iu1 = sub.hi[u] - box.lo[u];
  const int iv0 = sub.lo[v] - box.lo[v], iv1 = sub.hi[v] - box.lo[v];
  const int nu = iu1 - iu0 + 1;
  struct Column {
    double height;
    bool flipped;
    int count;
  };
  std::vector<Column> cols(static_cast<std::size_t>(nu) * (iv1 - iv0 + 1));
  const int lo = box.lo[a], hi = box.hi[a];
  for (int cv = sub.lo[v]; cv <= sub.hi[v]; ++cv)
    for (int cu = sub.lo[u]; cu <= sub.hi[u]; ++cu) {
      Column& c = cols[static_cast<std::size_t>(cv - sub.lo[v]) * nu + (cu - sub.lo[u])];
      if (!g.twoSidedColumn(d, cu, cv, c.height, c.flipped)) return TwoSidedCut::kInvalid;
      c.count = columnSolidCount(c.height, lo, hi, (d.sign > 0) != c.flipped);
      if (c.count == 0 || c.count == hi - lo + 1) c.flipped = false;  // as setColumn stores it
    }
  const auto inside = [&](int iu, int iv) {
    return iu >= iu0 && iu <= iu1 && iv >= iv0 && iv <= iv1;
  };
  const auto column = [&](int iu, int iv) -> const Column& {
    return cols[static_cast<std::size_t>(iv - iv0) * nu + (iu - iu0)];
  };
  const double before = volumeDelta != nullptr ? map.squaresVolume(iu0, iu1, iv0, iv1) : 0.0;
  // Rows through the footprint: edges with both columns in it from the cut grid, the
  // rest as they were (counted with the columns' old sides, so before any is set).
  std::vector<std::vector<double>> rows[2];
  if (map.threeWay()) {
    for (int family = 0; family < 2; ++family) {
      const int x = family == 0 ? u : v, y = family == 0 ? v : u;
      const int r0 = family == 0 ? iv0 : iu0, r1 = family == 0 ? iv1 : iu1;
      for (int r = r0; r <= r1; ++r) {
        const std::vector<double>& old = map.row(family, r);
        std::vector<double> out;
        out.reserve(old.size());
        std::size_t pos = 0;
        for (int e = 0; e < map.edgesInRow(family); ++e) {
          const int ua = family == 0 ? e : r, va = family == 0 ? r : e;
          const int ub = family == 0 ? e + 1 : r, vb = family == 0 ? r : e + 1;
          const int was = map.straddleEdge(family, r, e).total();
          if (!inside(ua, va) || !inside(ub, vb)) {
            out.insert(out.end(), old.begin() + static_cast<std::ptrdiff_t>(pos),
                       old.begin() + static_cast<std::ptrdiff_t>(pos + was));
            pos += was;
            continue;
          }
          pos += was;
          const Column& c0 = column(ua, va);
          const Column& c1 = column(ub, vb);
          const ColumnStraddle st = columnsStraddle(c0.count, (d.sign > 0) != c0.flipped, c1.count,
                                                    (d.sign > 0) != c1.flipped, lo, hi);
          appendEdgeCrossings(g, map, st, x, box.lo[x] + e, y, box.lo[y] + r, c0.height, c1.height,
                              out);
        }
        out.shrink_to_fit();
        rows[family].push_back(std::move(out));
      }
    }
  }
  for (int iv = iv0; iv <= iv1; ++iv)
    for (int iu = iu0; iu <= iu1; ++iu) {
      const Column& c = column(iu, iv);
      map.setColumn(iu, iv, c.height, c.flipped);
    }
  if (map.threeWay())
    for (int family = 0; family < 2; ++family) {
      const int r0 = family == 0 ? iv0 : iu0;
      for (std::size_t i = 0; i < rows[family].size(); ++i)
        map.row(family, r0 + static_cast<int>(i)).swap(rows[family][i]);
    }
  if (volumeDelta != nullptr) *volumeDelta = map.squaresVolume(iu0, iu1, iv0, iv1) - before;
  return TwoSidedCut::kDone;
}

}  // namespace mdhd::mdh

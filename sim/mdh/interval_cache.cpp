#include "sim/mdh/interval_cache.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace mdhd::mdh {

struct IntervalCache::Row {
  std::once_flag once;
  int first = 0;                       // first line index (on axis u) with intervals
  std::vector<std::uint32_t> offsets;  // per line from `first`, plus one end entry
  std::vector<Span> spans;
  mutable std::atomic<std::size_t> calls{0};
};

namespace {

// Coordinates within 1e-9 of a grid plane are snapped onto it, so a tool face
// that sits on a grid level in millimetres does so in grid units too.
double snap(double g) {
  const double r = std::round(g);
  return std::abs(g - r) < 1e-9 ? r : g;
}

}  // namespace

IntervalCache::IntervalCache(const GridSpec& grid, const geom::LineSolid& solid)
    : grid_(grid), solid_(solid) {
  const geom::Aabb b = solid.bounds();
  for (int a = 0; a < 3; ++a) {
    const double lo = grid.toGrid(a, b.lo[a]);
    const double hi = grid.toGrid(a, b.hi[a]);
    // Clamp in double first: a solid far outside must not overflow the cast.
    const double top = grid.cubes[a];
    const bool ok = std::isfinite(lo) && std::isfinite(hi) && lo <= hi;
    touched_.lo[a] = ok ? static_cast<int>(std::clamp(std::floor(lo), 0.0, top + 1.0)) : 1;
    touched_.hi[a] = ok ? static_cast<int>(std::clamp(std::ceil(hi), -1.0, top)) : 0;
  }
  if (touched_.empty()) return;
  for (int a = 0; a < 3; ++a) {
    const int nv = touched_.points(axisV(a));
    rows_[a].resize(nv);
    for (auto& r : rows_[a]) r = std::make_unique<Row>();
  }
}

IntervalCache::~IntervalCache() = default;

void IntervalCache::fill(int axis, Row& row, int iv) const {
  const int u = axisU(axis), v = axisV(axis);
  const double vmm = grid_.toMm(v, iv);
  std::vector<geom::Interval> buf;
  int first = -1;
  for (int iu = touched_.lo[u]; iu <= touched_.hi[u]; ++iu) {
    buf.clear();
    solid_.lineIntervals(axis, grid_.toMm(u, iu), vmm, buf);
    row.calls.fetch_add(1, std::memory_order_relaxed);
    const std::size_t start = row.spans.size();
    for (const geom::Interval& i : buf) {
      const Span s{snap(grid_.toGrid(axis, i.lo)), snap(grid_.toGrid(axis, i.hi))};
      if (s.hi > s.lo) row.spans.push_back(s);  // drops NaN and inverted intervals
    }
    // The contract says sorted and disjoint; make sure, the arithmetic relies on it.
    const auto begin = row.spans.begin() + static_cast<std::ptrdiff_t>(start);
    auto byLo = [](const Span& x, const Span& y) { return x.lo < y.lo; };
    if (!std::is_sorted(begin, row.spans.end(), byLo)) std::sort(begin, row.spans.end(), byLo);
    std::size_t kept = start;
    for (std::size_t k = start; k < row.spans.size(); ++k) {
      if (kept > start && row.spans[k].lo <= row.spans[kept - 1].hi)
        row.spans[kept - 1].hi = std::max(row.spans[kept - 1].hi, row.spans[k].hi);
      else
        row.spans[kept++] = row.spans[k];
    }
    row.spans.resize(kept);
    if (kept == start && first < 0) continue;  // leading empty lines are not stored
    if (first < 0) first = iu;
    row.offsets.push_back(static_cast<std::uint32_t>(start));
  }
  if (first < 0) return;
  // Trailing empty lines are dropped too: the row keeps its own extent.
  while (row.offsets.size() > 1 && row.offsets.back() == row.spans.size()) row.offsets.pop_back();
  row.first = first;
  row.offsets.push_back(static_cast<std::uint32_t>(row.spans.size()));
}

std::span<const Span> IntervalCache::line(int axis, int iu, int iv) const {
  if (touched_.empty()) return {};
  const int u = axisU(axis), v = axisV(axis);
  if (iu < touched_.lo[u] || iu > touched_.hi[u] || iv < touched_.lo[v] || iv > touched_.hi[v])
    return {};
  Row& row = *rows_[axis][iv - touched_.lo[v]];
  std::call_once(row.once, [&] { fill(axis, row, iv); });
  const int i = iu - row.first;
  if (row.offsets.empty() || i < 0 || i + 1 >= static_cast<int>(row.offsets.size())) return {};
  return std::span<const Span>(row.spans.data() + row.offsets[i],
                               row.offsets[i + 1] - row.offsets[i]);
}

std::size_t IntervalCache::queries() const {
  std::size_t n = 0;
  for (const auto& axisRows : rows_)
    for (const auto& r : axisRows) n += r->calls.load(std::memory_order_relaxed);
  return n;
}

}  // namespace mdhd::mdh

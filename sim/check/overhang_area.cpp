#include "sim/check/overhang_area.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <thread>
#include <vector>

namespace mdhd::check {
namespace {

// Where the lines of a region leave or enter solid, in grid units, line after line in
// one array per kind (no vector per line: a region holds a million lines): `lower`
// ends have solid after them along the axis (outward normal -axis), `upper` ends
// before them.
struct Crossings {
  std::vector<double> values[2];        // lower, upper
  std::vector<std::uint32_t> start[2];  // line i's are values[end][start[i] .. start[i + 1])
  std::span<const double> of(std::size_t line, int end) const {
    return std::span<const double>(values[end])
        .subspan(start[end][line], start[end][line + 1] - start[end][line]);
  }
};

std::optional<double> nearest(std::span<const double> values, double c, double within) {
  std::optional<double> best;
  for (double v : values)
    if (std::abs(v - c) <= within && (!best || std::abs(v - c) < std::abs(*best - c))) best = v;
  return best;
}

// Slope of the surface through crossing c across the neighbouring lines (grid units):
// nullopt when neither neighbour has a matching crossing (steeper than this axis sees).
std::optional<double> slope(const std::span<const double>* before,
                            const std::span<const double>* after, double c) {
  constexpr double kWithin = 1.5;
  const auto b = before != nullptr ? nearest(*before, c, kWithin) : std::nullopt;
  const auto a = after != nullptr ? nearest(*after, c, kWithin) : std::nullopt;
  if (a && b) return 0.5 * (*a - *b);
  if (a) return *a - c;
  if (b) return c - *b;
  return std::nullopt;
}

// The box of grid vertices that leaves other than +z heightmaps (two-sided ones
// included) cover, grown by one.
std::optional<mdh::GridBox> overhangRegion(const mdh::Stock& stock) {
  std::optional<mdh::GridBox> box;
  stock.forEachLeaf([&](const mdh::LeafView& leaf) {
    if (leaf.map == nullptr ||
        (leaf.map->direction() == mdh::Direction{2, 1} && !leaf.map->hasFlips()))
      return;
    if (!box) {
      box = leaf.box;
      return;
    }
    for (int a = 0; a < 3; ++a) {
      box->lo[a] = std::min(box->lo[a], leaf.box.lo[a]);
      box->hi[a] = std::max(box->hi[a], leaf.box.hi[a]);
    }
  });
  if (box) {
    const auto& cubes = stock.grid().cubes;
    for (int a = 0; a < 3; ++a) {
      box->lo[a] = std::max(0, box->lo[a] - 1);
      box->hi[a] = std::min(cubes[a], box->hi[a] + 1);
    }
  }
  return box;
}

// The crossings of the region's lines of `axis` in rows [v0, v1), line after line.
void readRows(const mdh::Stock& stock, const mdh::GridBox& box, int axis, int v0, int v1,
              Crossings& lines) {
  const mdh::GridSpec& g = stock.grid();
  const int u = mdh::axisU(axis), v = mdh::axisV(axis);
  const int nu = box.points(u);
  std::vector<geom::Interval> spans;
  const double lo = box.lo[axis], hi = box.hi[axis];
  for (int jv = v0; jv < v1; ++jv)
    for (int ju = 0; ju < nu; ++ju) {
      stock.solidIntervals(axis, box.lo[u] + ju, box.lo[v] + jv, spans);
      for (int end = 0; end < 2; ++end)
        lines.start[end].push_back(static_cast<std::uint32_t>(lines.values[end].size()));
      for (const geom::Interval& s : spans) {
        const double a = g.toGrid(axis, s.lo), b = g.toGrid(axis, s.hi);
        // The stock box's own faces are raw material, not machined surface.
        if (a > 1e-9 && a >= lo && a <= hi) lines.values[0].push_back(a);
        if (b < g.cubes[axis] - 1e-9 && b >= lo && b <= hi) lines.values[1].push_back(b);
      }
    }
}

double axisArea(const mdh::Stock& stock, const mdh::GridBox& box, int axis, int threads) {
  const mdh::GridSpec& g = stock.grid();
  const int u = mdh::axisU(axis), v = mdh::axisV(axis);
  const int nu = box.points(u), nv = box.points(v);
  // Reading the lines (the stock's queries, const) is most of the work: on `threads`
  // threads, a band of rows each, joined in row order. The sum below stays on one
  // thread, in one order, so the area is the same to the bit whatever the count.
  const int parts = std::clamp(threads, 1, std::max(1, nv / 16));
  std::vector<Crossings> band(static_cast<std::size_t>(parts));
  const auto rowOf = [&](int p) { return static_cast<int>(std::int64_t(nv) * p / parts); };
  {
    std::vector<std::jthread> helpers;
    for (int p = 1; p < parts; ++p)
      helpers.emplace_back(
          [&, p] { readRows(stock, box, axis, rowOf(p), rowOf(p + 1), band[std::size_t(p)]); });
    readRows(stock, box, axis, rowOf(0), rowOf(1), band[0]);
  }
  Crossings lines = std::move(band[0]);
  for (std::size_t p = 1; p < band.size(); ++p)
    for (int end = 0; end < 2; ++end) {
      const auto offset = static_cast<std::uint32_t>(lines.values[end].size());
      for (std::uint32_t s : band[p].start[end]) lines.start[end].push_back(s + offset);
      lines.values[end].insert(lines.values[end].end(), band[p].values[end].begin(),
                               band[p].values[end].end());
    }
  for (int end = 0; end < 2; ++end)
    lines.start[end].push_back(static_cast<std::uint32_t>(lines.values[end].size()));
  // Another axis sees this surface at a better angle, or as well and comes first (a
  // wall at 45 degrees between two axes, as a hole tilted 45 degrees has all round,
  // was counted on the lines of both: +12-18 %): it counts it there.
  constexpr double kTie = 1e-3;
  const auto yields = [axis](double s, int other) {
    return std::abs(s) > 1.0 + kTie || (std::abs(s) >= 1.0 - kTie && other < axis);
  };
  double area = 0.0;
  for (int jv = 0; jv < nv; ++jv)
    for (int ju = 0; ju < nu; ++ju) {
      const std::size_t here = static_cast<std::size_t>(jv) * nu + ju;
      for (int end = 0; end < 2; ++end) {
        // A neighbour's crossings of the same kind, or none outside the region.
        const auto at = [&](int iu, int iv, std::span<const double>& out) {
          if (iu < 0 || iv < 0 || iu >= nu || iv >= nv) return false;
          out = lines.of(static_cast<std::size_t>(iv) * nu + iu, end);
          return true;
        };
        std::span<const double> bu, au, bv, av;
        const std::span<const double>* beforeU = at(ju - 1, jv, bu) ? &bu : nullptr;
        const std::span<const double>* afterU = at(ju + 1, jv, au) ? &au : nullptr;
        const std::span<const double>* beforeV = at(ju, jv - 1, bv) ? &bv : nullptr;
        const std::span<const double>* afterV = at(ju, jv + 1, av) ? &av : nullptr;
        for (double c : lines.of(here, end)) {
          const auto su = slope(beforeU, afterU, c);
          const auto sv = slope(beforeV, afterV, c);
          if (!su || !sv || yields(*su, u) || yields(*sv, v)) continue;
          const double norm = std::sqrt(1.0 + *su * *su + *sv * *sv);
          // Outward normal: -axis at a lower end (solid after it), +axis at an upper end.
          const double sign = end == 0 ? -1.0 : 1.0;
          double n[3];
          n[axis] = sign / norm;
          n[u] = -sign * *su / norm;
          n[v] = -sign * *sv / norm;
          if (n[2] < kOverhangNormalZ) area += norm;
        }
      }
    }
  return area * g.h * g.h;
}

}  // namespace

double overhangArea(const mdh::Stock& stock, int threads) {
  const auto box = overhangRegion(stock);
  if (!box) return 0.0;
  double area = 0.0;
  for (int axis = 0; axis < 3; ++axis) area += axisArea(stock, *box, axis, threads);
  return area;
}

}  // namespace mdhd::check

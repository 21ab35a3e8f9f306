#include "sim/mdh/three_map.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace mdhd::mdh {

ThreeMap::ThreeMap(const GridBox& box, Direction dir, bool threeWay)
    : box_(box),
      dir_(dir),
      threeWay_(threeWay),
      nu_(box.points(axisU(dir.axis))),
      nv_(box.points(axisV(dir.axis))),
      fullColumns_(nu_ * nv_) {
  heights_.assign(static_cast<std::size_t>(nu_) * nv_, fullHeight());
  if (threeWay_) {
    rows_[0].resize(nv_);
    rows_[1].resize(nu_);
  }
}

void ThreeMap::straddle(double h1, double h2, int& first, int& count) const {
  const int f1 = solidCount(h1);
  const int f2 = solidCount(h2);
  count = std::abs(f1 - f2);
  first = dir_.sign > 0 ? box_.lo[dir_.axis] + std::min(f1, f2)
                        : box_.hi[dir_.axis] - std::max(f1, f2) + 1;
}

double ThreeMap::interpolatedCrossing(double h0, double h1, int edgeStart, int level) const {
  const double lo = box_.lo[dir_.axis] - 1.0;
  const double hi = box_.hi[dir_.axis] + 1.0;
  h0 = std::clamp(h0, lo, hi);
  h1 = std::clamp(h1, lo, hi);
  if (h0 == h1) return edgeStart + 0.5;
  const double t = std::clamp((level - h0) / (h1 - h0), 0.0, 1.0);
  return edgeStart + t;
}

namespace {

// Integral over one edge of the solid length, through (0, len0), the
// embedded crossings and (1, len1).
double edgeIntegral(double len0, double len1, const std::vector<std::pair<double, double>>& pts) {
  if (pts.empty()) return 0.5 * (len0 + len1);
  double x = 0.0, f = len0, sum = 0.0;
  for (const auto& [px, pf] : pts) {
    sum += 0.5 * (f + pf) * (px - x);
    x = px;
    f = pf;
  }
  return sum + 0.5 * (f + len1) * (1.0 - x);
}

}  // namespace

double ThreeMap::squaresVolume(int iu0, int iu1, int iv0, int iv1) const {
  if (iu1 <= iu0 || iv1 <= iv0) return 0.0;
  const int a = dir_.axis;
  const double lo = box_.lo[a], hi = box_.hi[a];
  auto levelLength = [&](int k) { return dir_.sign > 0 ? k - lo : hi - k; };
  std::vector<std::pair<double, double>> pts;
  // Edge integrals of one row, edges [e0, e1). Solid counts are computed
  // once per column; the walk up to e0 only sums how many crossings to skip.
  std::vector<int> counts;
  auto rowIntegrals = [&](int family, int r, int e0, int e1, std::vector<double>& out) {
    out.resize(e1 - e0);
    counts.resize(e1 + 1);
    for (int e = 0; e <= e1; ++e) counts[e] = solidCount(rowHeight(family, r, e));
    std::size_t pos = 0;
    for (int e = 0; e < e0; ++e) pos += std::abs(counts[e] - counts[e + 1]);
    const int base = box_.lo[family == 0 ? uAxis() : vAxis()];
    for (int e = e0; e < e1; ++e) {
      const double h0 = rowHeight(family, r, e), h1 = rowHeight(family, r, e + 1);
      const int f0 = counts[e], f1 = counts[e + 1];
      const int count = std::abs(f0 - f1);
      const int first =
          dir_.sign > 0 ? box_.lo[a] + std::min(f0, f1) : box_.hi[a] - std::max(f0, f1) + 1;
      const double len0 = columnLength(h0), len1 = columnLength(h1);
      pts.clear();
      for (int i = 0; threeWay_ && i < count; ++i)
        pts.emplace_back(std::clamp(rows_[family][r][pos + i] - (base + e), 0.0, 1.0),
                         levelLength(first + i));
      // Crossings at the same spot form a vertical step: walk it from the
      // first column's height towards the second's.
      if (pts.size() > 1)
        std::sort(pts.begin(), pts.end(), [&](const auto& x, const auto& y) {
          if (x.first != y.first) return x.first < y.first;
          return len0 > len1 ? x.second > y.second : x.second < y.second;
        });
      out[e - e0] = edgeIntegral(len0, len1, pts);
      pos += count;
    }
  };
  double sum = 0.0;
  std::vector<double> edges;
  for (int iv = iv0; iv <= iv1; ++iv) {  // edges along u, each in 1 or 2 squares
    rowIntegrals(0, iv, iu0, iu1, edges);
    const double w = (iv == iv0 || iv == iv1) ? 0.5 : 1.0;
    for (double x : edges) sum += w * x;
  }
  for (int iu = iu0; iu <= iu1; ++iu) {
    rowIntegrals(1, iu, iv0, iv1, edges);
    const double w = (iu == iu0 || iu == iu1) ? 0.5 : 1.0;
    for (double x : edges) sum += w * x;
  }
  for (int iv = iv0; iv <= iv1; ++iv)
    for (int iu = iu0; iu <= iu1; ++iu) {
      const int squares = (iu == iu0 || iu == iu1 ? 1 : 2) * (iv == iv0 || iv == iv1 ? 1 : 2);
      sum -= 0.25 * squares * columnLength(height(iu, iv));
    }
  return sum;
}

std::size_t ThreeMap::memoryBytes() const {
  std::size_t bytes = sizeof(ThreeMap) + heights_.capacity() * sizeof(double);
  for (const auto& family : rows_) {
    bytes += family.capacity() * sizeof(std::vector<double>);
    for (const auto& r : family) bytes += r.capacity() * sizeof(double);
  }
  return bytes;
}

std::size_t ThreeMap::embeddedCount() const {
  std::size_t n = 0;
  for (const auto& family : rows_)
    for (const auto& r : family) n += r.size();
  return n;
}

ThreeMap ThreeMap::restrictedTo(const GridBox& sub) const {
  ThreeMap out(sub, dir_, threeWay_);
  const int u = uAxis(), v = vAxis();
  const int du = sub.lo[u] - box_.lo[u];
  const int dv = sub.lo[v] - box_.lo[v];
  for (int iv = 0; iv < out.nv_; ++iv) {
    for (int iu = 0; iu < out.nu_; ++iu) {
      double h = height(iu + du, iv + dv);
      // Clamp into the child's extent along the direction axis.
      const int n = out.solidCount(h);
      if (n == 0)
        h = out.emptyHeight();
      else if (n == out.levels())
        h = out.fullHeight();
      out.setHeight(iu, iv, h);
    }
  }
  if (!threeWay_) return out;
  for (int family = 0; family < 2; ++family) {
    const int rowOffset = family == 0 ? dv : du;
    const int edgeOffset = family == 0 ? du : dv;
    for (int r = 0; r < out.rowCount(family); ++r) {
      const std::vector<double>& src = row(family, r + rowOffset);
      std::vector<double>& dst = out.row(family, r);
      std::size_t pos = 0;
      for (int e = 0; e < edgesInRow(family); ++e) {
        int first = 0, count = 0;
        straddle(rowHeight(family, r + rowOffset, e), rowHeight(family, r + rowOffset, e + 1),
                 first, count);
        const int le = e - edgeOffset;
        if (le >= 0 && le < out.edgesInRow(family)) {
          int cFirst = 0, cCount = 0;
          out.straddle(out.rowHeight(family, r, le), out.rowHeight(family, r, le + 1), cFirst,
                       cCount);
          for (int i = 0; i < cCount; ++i) dst.push_back(src[pos + (cFirst + i - first)]);
        }
        pos += count;
      }
      dst.shrink_to_fit();
    }
  }
  return out;
}

}  // namespace mdhd::mdh

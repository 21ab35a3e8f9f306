#include "sim/mdh/three_map.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <utility>

namespace mdhd::mdh {

ThreeMap::ThreeMap(const GridBox& box, Direction dir, bool threeWay)
    : box_(box),
      dir_(dir),
      threeWay_(threeWay),
      nu_(box.points(axisU(dir.axis))),
      nv_(box.points(axisV(dir.axis))),
      fullColumns_(nu_ * nv_) {
  columns_ = ColumnTiles(nu_, nv_, fullHeight(), emptyHeight());
  if (threeWay_) {
    rows_[0].resize(nv_);
    rows_[1].resize(nu_);
  }
}

void ThreeMap::setColumn(int iu, int iv, double h, bool flip) {
  const int lo = box_.lo[dir_.axis], hi = box_.hi[dir_.axis];
  const bool was = flipped(iu, iv);
  const int before = columnSolidCount(height(iu, iv), lo, hi, (dir_.sign > 0) != was);
  const int after = columnSolidCount(h, lo, hi, (dir_.sign > 0) != flip);
  if (after == 0 || after == levels()) {
    h = after == 0 ? emptyHeight() : fullHeight();
    flip = false;
  }
  if (flip != was) flips_ += flip ? 1 : -1;
  store(iu, iv, h, flip, before, after);
}

void ThreeMap::rowColumns(int family, int index, int n, double* heights, std::uint8_t* ups,
                          int* counts) const {
  rowHeights(family, index, 0, n, heights);
  const int lo = box_.lo[dir_.axis], hi = box_.hi[dir_.axis];
  const bool mapUp = dir_.sign > 0;
  for (int e = 0; e < n; ++e) {
    ups[e] = flips_ == 0 ? mapUp : (family == 0 ? columnUp(e, index) : columnUp(index, e));
    counts[e] = columnSolidCount(heights[e], lo, hi, ups[e] != 0);
  }
}

void ThreeMap::straddle(double h1, double h2, int& first, int& count) const {
  straddleCounts(solidCount(h1), solidCount(h2), first, count);
}

double ThreeMap::edgeCrossing(int family, int index, int edge, int level) const {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  if (!threeWay_) return kNone;
  const int at = straddleEdge(family, index, edge).indexOf(level);
  if (at < 0) return kNone;
  std::size_t pos = 0;
  for (int e = 0; e < edge; ++e) pos += straddleEdge(family, index, e).total();
  const std::vector<double>& r = rows_[family][index];
  return pos + at < r.size() ? r[pos + at] : kNone;
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

using Point = std::pair<double, double>;  // (position along the edge, solid length)

// Integral over one edge of the solid length, through (0, len0), the
// embedded crossings and (1, len1).
double polylineIntegral(double len0, double len1, const Point* pts, std::size_t n) {
  double x = 0.0, f = len0, sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += 0.5 * (f + pts[i].second) * (pts[i].first - x);
    x = pts[i].first;
    f = pts[i].second;
  }
  return sum + 0.5 * (f + len1) * (1.0 - x);
}

}  // namespace

// f0, f1: the two columns' solid counts; len0, len1: their solid lengths; up: the
// side both columns are on (columns on opposite sides: mixedEdgeIntegral).
double ThreeMap::profileIntegral(int f0, int f1, double len0, double len1, int edgeStart,
                                 const double* crossings, bool up) const {
  const int a = dir_.axis;
  int first = 0, count = 0;
  columnStraddle(f0, f1, box_.lo[a], box_.hi[a], up, first, count);
  if (!threeWay_ || count == 0) return 0.5 * (len0 + len1);
  const double lo = box_.lo[a], hi = box_.hi[a];
  if (count == 1) {
    const Point p{std::clamp(crossings[0] - edgeStart, 0.0, 1.0), up ? first - lo : hi - first};
    return polylineIntegral(len0, len1, &p, 1);
  }
  thread_local std::vector<Point> pts;
  pts.resize(count);
  for (int i = 0; i < count; ++i)
    pts[i] = {std::clamp(crossings[i] - edgeStart, 0.0, 1.0),
              up ? first + i - lo : hi - (first + i)};
  // The profile meets each level between the two columns once: walk the levels from
  // the first column's height towards the second's, keeping the positions from going
  // back. (Sorted by position, a wall's crossings, equal but for their last bits,
  // came in any level order, and the profile jumped across the wall's height: a hole
  // drilled with a 170-degree tip, whose floor puts the wall's foot off the levels,
  // read up to 1.2 % too large.)
  if ((pts.front().second > pts.back().second) != (len0 > len1))
    std::reverse(pts.begin(), pts.end());
  for (int i = 1; i < count; ++i) pts[i].first = std::max(pts[i].first, pts[i - 1].first);
  return polylineIntegral(len0, len1, pts.data(), pts.size());
}

// An edge between columns on opposite sides (the up column's solid from the low face,
// the down column's from the high one), its crossings the straddle's low run (only the
// up column solid there) then its high run. Solids apart in level (a gap between): two
// profiles, each a column's solid against an empty column. Solids overlapping (a band
// solid across the edge): the edge's length less two empty profiles, the down column's
// empty run below it against the low run and the up column's above it against the high
// run. Each profile is a one-sided edge's, so as exact as one.
double ThreeMap::mixedEdgeIntegral(int f0, int f1, double len0, double len1, bool up0,
                                   int edgeStart, const double* crossings) const {
  const int fu = up0 ? f0 : f1, fd = up0 ? f1 : f0, n = levels();
  if (!threeWay_ || crossings == nullptr) return 0.5 * (len0 + len1);
  const double lu = up0 ? len0 : len1, ld = up0 ? len1 : len0;
  if (fu + fd > n) {
    const double length = box_.hi[dir_.axis] - box_.lo[dir_.axis];
    const int eu = n - fd, ed = n - fu;  // the empty runs' counts
    const double* high = crossings + eu;
    const double emptyLow =
        up0 ? profileIntegral(0, eu, 0.0, length - ld, edgeStart, crossings, true)
            : profileIntegral(eu, 0, length - ld, 0.0, edgeStart, crossings, true);
    const double emptyHigh = up0 ? profileIntegral(ed, 0, length - lu, 0.0, edgeStart, high, false)
                                 : profileIntegral(0, ed, 0.0, length - lu, edgeStart, high, false);
    return length - emptyLow - emptyHigh;
  }
  // Crossings ascend by level: the up column's run (fu of them) first.
  const double upPart = up0 ? profileIntegral(fu, 0, lu, 0.0, edgeStart, crossings, true)
                            : profileIntegral(0, fu, 0.0, lu, edgeStart, crossings, true);
  const double* high = crossings + fu;
  const double downPart = up0 ? profileIntegral(0, fd, 0.0, ld, edgeStart, high, false)
                              : profileIntegral(fd, 0, ld, 0.0, edgeStart, high, false);
  return upPart + downPart;
}

double ThreeMap::edgeIntegral(double h0, double h1, int edgeStart, const double* crossings) const {
  return profileIntegral(solidCount(h0), solidCount(h1), columnLength(h0), columnLength(h1),
                         edgeStart, crossings, dir_.sign > 0);
}

double ThreeMap::squaresVolume(int iu0, int iu1, int iv0, int iv1) const {
  if (iu1 <= iu0 || iv1 <= iv0) return 0.0;
  // Edge integrals of one row, edges [e0, e1). Solid counts are computed
  // once per column; the walk up to e0 only sums how many crossings to skip.
  thread_local std::vector<int> counts;
  thread_local std::vector<std::uint8_t> ups;
  thread_local std::vector<double> lengths;
  const int lo = box_.lo[dir_.axis], hi = box_.hi[dir_.axis];
  const int nu = iu1 - iu0, nv = iv1 - iv0;  // squares
  double* endsU = nullptr;
  double* endsV = nullptr;
  if (threeWay_) cornerScratch(nu, nv, endsU, endsV);
  auto rowSum = [&](int family, int r, int e0, int e1, double* ends) {
    counts.resize(e1 + 1);
    ups.resize(e1 + 1);
    lengths.resize(e1 + 1);
    rowColumns(family, r, e1 + 1, lengths.data(), ups.data(), counts.data());
    for (int e = 0; e <= e1; ++e) lengths[e] = lengthOf(lengths[e], ups[e] != 0);  // heights in
    const auto crossingsAt = [&](int e) {
      return columnsStraddle(counts[e], ups[e], counts[e + 1], ups[e + 1], lo, hi).total();
    };
    std::size_t pos = 0;
    for (int e = 0; e < e0; ++e) pos += crossingsAt(e);
    const int base = box_.lo[family == 0 ? uAxis() : vAxis()];
    const double* row = threeWay_ ? rows_[family][r].data() : nullptr;
    double sum = 0.0;
    for (int e = e0; e < e1; ++e) {
      const double len0 = lengths[e], len1 = lengths[e + 1];
      // Full and empty columns are unflipped: opposite sides mean crossings at both ends.
      if (ups[e] != ups[e + 1]) {
        sum += mixedEdgeIntegral(counts[e], counts[e + 1], len0, len1, ups[e] != 0, base + e,
                                 row != nullptr ? row + pos : nullptr);
        if (ends != nullptr) ends[2 * (e - e0)] = ends[2 * (e - e0) + 1] = kAgrees;
      } else {
        sum += profileIntegral(counts[e], counts[e + 1], len0, len1, base + e,
                               row != nullptr ? row + pos : nullptr, ups[e] != 0);
        if (ends != nullptr)
          profileEnds(counts[e], counts[e + 1], len0, len1, base + e, row + pos, ups[e] != 0,
                      ends + 2 * (e - e0));
      }
      pos += crossingsAt(e);
    }
    return sum;
  };
  double sum = 0.0;
  for (int iv = iv0; iv <= iv1; ++iv)  // edges along u, each in 1 or 2 squares
    sum += ((iv == iv0 || iv == iv1) ? 0.5 : 1.0) *
           rowSum(0, iv, iu0, iu1, endsU != nullptr ? endsU + 2 * nu * (iv - iv0) : nullptr);
  for (int iu = iu0; iu <= iu1; ++iu)
    sum += ((iu == iu0 || iu == iu1) ? 0.5 : 1.0) *
           rowSum(1, iu, iv0, iv1, endsV != nullptr ? endsV + 2 * nv * (iu - iu0) : nullptr);
  for (int iv = iv0; iv <= iv1; ++iv)
    for (int iu = iu0; iu <= iu1; ++iu) {
      const int squares = (iu == iu0 || iu == iu1 ? 1 : 2) * (iv == iv0 || iv == iv1 ? 1 : 2);
      sum -= 0.25 * squares * columnLengthAt(iu, iv);
    }
  if (endsU != nullptr) sum += cornerSum(iu0, iu1, iv0, iv1, endsU, endsV);
  return sum;
}

void ThreeMap::profileEnds(int f0, int f1, double len0, double len1, int edgeStart,
                           const double* crossings, bool up, double* ends) const {
  ends[0] = ends[1] = kAgrees;
  const int a = dir_.axis;
  int first = 0, count = 0;
  columnStraddle(f0, f1, box_.lo[a], box_.hi[a], up, first, count);
  if (!threeWay_ || count == 0) return;
  const double lo = box_.lo[a], hi = box_.hi[a];
  const auto value = [&](int i) { return up ? first + i - lo : hi - (first + i); };
  // profileIntegral's walk: by level from the first column's height, positions kept
  // from going back; a run of points at 0 leads, the first point at 1 ends the slope.
  // "At" an end is within kAtEnd: a crossing on a grid vertex is stored a bit off it
  // (on the solid side), and a surface a rounding error off a vertex is on it.
  constexpr double kAtEnd = 1e-6;
  const bool reversed = count > 1 && (value(0) > value(count - 1)) != (len0 > len1);
  double run = 0.0;
  double end0 = len0;
  for (int k = 0; k < count; ++k) {
    const int i = reversed ? count - 1 - k : k;
    run = std::max(run, std::clamp(crossings[i] - edgeStart, 0.0, 1.0));
    if (run <= kAtEnd) end0 = value(i);
    if (run >= 1.0 - kAtEnd) {
      if (value(i) != len1) ends[1] = value(i);
      break;
    }
  }
  if (end0 != len0) ends[0] = end0;
}

void ThreeMap::cornerScratch(int nu, int nv, double*& endsU, double*& endsV) {
  thread_local std::vector<double> u, v;  // [row][edge][end]
  u.resize(static_cast<std::size_t>(nv + 1) * nu * 2);
  v.resize(static_cast<std::size_t>(nu + 1) * nv * 2);
  endsU = u.data();
  endsV = v.data();
}

double ThreeMap::cornerCorrection(int iu0, int iu1, int iv0, int iv1) const {
  if (!threeWay_ || iu1 <= iu0 || iv1 <= iv0) return 0.0;
  const int nu = iu1 - iu0, nv = iv1 - iv0;
  double* endsU = nullptr;
  double* endsV = nullptr;
  cornerScratch(nu, nv, endsU, endsV);
  thread_local std::vector<int> counts;
  thread_local std::vector<std::uint8_t> ups;
  thread_local std::vector<double> lengths;
  const int lo = box_.lo[dir_.axis], hi = box_.hi[dir_.axis];
  const auto rowEnds = [&](int family, int r, int e0, int e1, double* ends) {
    counts.resize(e1 + 1);
    ups.resize(e1 + 1);
    lengths.resize(e1 + 1);
    rowColumns(family, r, e1 + 1, lengths.data(), ups.data(), counts.data());
    const int base = box_.lo[family == 0 ? uAxis() : vAxis()];
    const double* row = rows_[family][r].data();
    std::size_t pos = 0;
    for (int e = 0; e < e1; ++e) {
      const int n = columnsStraddle(counts[e], ups[e], counts[e + 1], ups[e + 1], lo, hi).total();
      if (e >= e0) {
        double* out = ends + 2 * (e - e0);
        if (ups[e] != ups[e + 1] || n == 0)
          out[0] = out[1] = kAgrees;
        else
          profileEnds(counts[e], counts[e + 1], lengthOf(lengths[e], ups[e] != 0),
                      lengthOf(lengths[e + 1], ups[e + 1] != 0), base + e, row + pos, ups[e] != 0,
                      out);
      }
      pos += static_cast<std::size_t>(n);
    }
  };
  for (int iv = iv0; iv <= iv1; ++iv) rowEnds(0, iv, iu0, iu1, endsU + 2 * nu * (iv - iv0));
  for (int iu = iu0; iu <= iu1; ++iu) rowEnds(1, iu, iv0, iv1, endsV + 2 * nv * (iu - iu0));
  return cornerSum(iu0, iu1, iv0, iv1, endsU, endsV);
}

double ThreeMap::cornerSum(int iu0, int iu1, int iv0, int iv1, const double* endsU,
                           const double* endsV) const {
  const int nu = iu1 - iu0, nv = iv1 - iv0;
  // Ends of the u edge of row iv starting at column iu (end 0 at iu, 1 at iu + 1).
  const auto uEnd = [&](int iu, int iv, int end) {
    return endsU[2 * nu * (iv - iv0) + 2 * (iu - iu0) + end];
  };
  const auto vEnd = [&](int iu, int iv, int end) {
    return endsV[2 * nv * (iu - iu0) + 2 * (iv - iv0) + end];
  };
  double sum = 0.0;
  const auto corner = [&](int iu, int iv, double eu, double ev) {
    if (std::isnan(eu) || std::isnan(ev)) return;  // an edge agrees with the column
    sum += 0.25 * (columnLengthAt(iu, iv) - 0.5 * (eu + ev));
  };
  for (int iv = iv0; iv < iv1; ++iv)
    for (int iu = iu0; iu < iu1; ++iu) {
      corner(iu, iv, uEnd(iu, iv, 0), vEnd(iu, iv, 0));
      corner(iu + 1, iv, uEnd(iu, iv, 1), vEnd(iu + 1, iv, 0));
      corner(iu, iv + 1, uEnd(iu, iv + 1, 0), vEnd(iu, iv, 1));
      corner(iu + 1, iv + 1, uEnd(iu, iv + 1, 1), vEnd(iu + 1, iv, 1));
    }
  return sum;
}

std::size_t ThreeMap::memoryBytes() const {
  std::size_t bytes = sizeof(ThreeMap) + columns_.memoryBytes();
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
  // setColumn clamps into the child's extent along the direction axis.
  out.reserveAllColumns();
  for (int iv = 0; iv < out.nv_; ++iv)
    for (int iu = 0; iu < out.nu_; ++iu)
      out.setColumn(iu, iv, height(iu + du, iv + dv), flipped(iu + du, iv + dv));
  out.releaseSlack();
  if (!threeWay_) return out;
  for (int family = 0; family < 2; ++family) {
    const int rowOffset = family == 0 ? dv : du;
    const int edgeOffset = family == 0 ? du : dv;
    for (int r = 0; r < out.rowCount(family); ++r) {
      const std::vector<double>& src = row(family, r + rowOffset);
      std::vector<double>& dst = out.row(family, r);
      std::size_t pos = 0;
      for (int e = 0; e < edgesInRow(family); ++e) {
        const ColumnStraddle from = straddleEdge(family, r + rowOffset, e);
        const int le = e - edgeOffset;
        if (le >= 0 && le < out.edgesInRow(family)) {
          const ColumnStraddle to = out.straddleEdge(family, r, le);
          for (int i = 0; i < to.total(); ++i) dst.push_back(src[pos + from.indexOf(to.level(i))]);
        }
        pos += from.total();
      }
      dst.shrink_to_fit();
    }
  }
  return out;
}

}  // namespace mdhd::mdh

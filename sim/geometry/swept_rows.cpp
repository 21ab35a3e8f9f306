// SweptVolume's answers for many lines at once: body by body, each body's lines
// through a branch-free kernel (axialExtentRow for lines along a 3-axis tool,
// crossExtentRow for lines square to it), the same answers to the bit as asking
// line by line (lineIntervals), for less per line.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "sim/geometry/row_targets.h"
#include "sim/geometry/swept_volume.h"

namespace mdhd::geom {

namespace {

inline double coord(const glm::dvec3& v, int i) {
  return glm::value_ptr(v)[i];
}

// Each line's union so far, body by body: while every interval meets the union of
// those before it, the union is one interval, their hull (what sorting and merging
// gives, to the bit). A line where one does not (rare: a chain crossing a line
// twice) is marked apart, to be asked again on its own. Arrays of their own, flags
// as wide as the doubles, so that the merge over lines vectorises.
struct Hulls {
  std::vector<std::uint64_t> any, apart;
  std::vector<double> lo, hi;

  void reset(std::size_t n) {
    any.assign(n, 0);
    apart.assign(n, 0);
    lo.resize(n);
    hi.resize(n);
  }
  // Appends line i's intervals for every line; `again(i)` asks a line apart on its own.
  template <class Again>
  void emit(std::vector<Interval>& out, std::span<std::size_t> ends, Again again) const {
    for (std::size_t i = 0; i < ends.size(); ++i) {
      if (apart[i])
        again(i);
      else if (any[i])
        out.push_back(Interval{lo[i], hi[i]});
      ends[i] = out.size();
    }
  }
};

// Adds interval i of a body (from `lane(i, lo, hi)`, which says whether it holds
// one) to line i's hull, for n lines from `any` etc. on (restrict holds for
// parameters only: every array comes in as one).
template <class Lane>
[[gnu::always_inline]] inline void mergeLanes(std::size_t n, Lane lane,
                                              std::uint64_t* __restrict any,
                                              std::uint64_t* __restrict apart,
                                              double* __restrict hlo, double* __restrict hhi) {
  using M = std::uint64_t;
  for (std::size_t i = 0; i < n; ++i) {
    double ilo, ihi;
    const M valid = lane(i, ilo, ihi);
    const M had = any[i];
    const M meets = M(ilo <= hhi[i]) & M(hlo[i] <= ihi);
    apart[i] |= valid & had & (meets ^ 1);
    const double nlo = had != 0 ? std::min(hlo[i], ilo) : ilo;
    const double nhi = had != 0 ? std::max(hhi[i], ihi) : ihi;
    hlo[i] = valid != 0 ? nlo : hlo[i];
    hhi[i] = valid != 0 ? nhi : hhi[i];
    any[i] = had | valid;
  }
}

// A body on the lines' axis: its intervals on lines [b, b + m) from axialExtentRow's
// heights (axialInterval, inlined).
MDHD_ROW_TARGETS void mergeAxial(double base, bool up, std::size_t b, std::size_t m,
                                 const double* __restrict lo, const double* __restrict hi,
                                 const unsigned char* __restrict hit, Hulls& h) {
  using M = std::uint64_t;
  const auto lane = [&](std::size_t j, double& ilo, double& ihi) {
    ilo = up ? base + lo[j] : base - hi[j];
    ihi = up ? base + hi[j] : base - lo[j];
    return M(hit[j] != 0) & M(ihi > ilo);
  };
  mergeLanes(m, lane, h.any.data() + b, h.apart.data() + b, h.lo.data() + b, h.hi.data() + b);
}

// crossLinesIntervals' arrays: per line (n), and per line of the piece at hand (k);
// each line's union so far as its hull, in arrays of its own so that the loops
// over lines vectorise.
struct CrossScratch {
  // Flags as wide as the doubles beside them: loops mixing widths do not vectorise.
  Hulls hulls;
  std::vector<std::uint64_t> keep, on;
  std::vector<double> zeta, h0, za, zb, lo, hi;
  std::vector<std::uint32_t> idx;
  std::vector<double> pz, ph, plo, phi;
  std::vector<unsigned char> hit;

  void reset(std::size_t n) {
    hulls.reset(n);
    keep.resize(n);  // both written whole before they are read
    on.resize(n);
    hit.resize(n);
    for (auto* v : {&zeta, &h0, &za, &zb, &lo, &hi, &pz, &ph, &plo, &phi}) v->resize(n);
    idx.resize(n);
  }
};

// What crossBodyInterval needs of a body, as locals.
struct BodyFrame {
  double u0, u1, v0, v1;  // its box across the lines
  double a0, a1;          // and along them
  double tip1, tip2;
  glm::dvec3 axis, normal;
  double rise;  // length * zd: how far along its axis the move goes
  double linearTol;
};

struct PieceFrame {
  double z0, z1, u0, u1, v0, v1;
};

// Each line's height on the body's axis and distance across its move, and whether
// the body may add to the line: its box holds the line and the line's union so far
// does not hold the box along it (lineIntervals skips those too: consecutive steps
// of a pass, seen from across it). kAxis: the lines' axis, so that the products
// are crossBodyInterval's, in its order (glm::dot of a vector with a zero there).
template <int kAxis>
[[gnu::always_inline]] inline std::uint64_t bodyLinesOn(
    const BodyFrame& f, const double* __restrict us, const double* __restrict vs, std::size_t n,
    const std::uint64_t* __restrict any, const std::uint64_t* __restrict apart,
    const double* __restrict hlo, const double* __restrict hhi, std::uint64_t* __restrict keep,
    double* __restrict zeta, double* __restrict h0, double* __restrict za, double* __restrict zb,
    double* __restrict lo, double* __restrict hi) {
  // (Restrict holds for parameters only: every array comes in as one.)
  constexpr int k1 = (kAxis + 1) % 3, k2 = (kAxis + 2) % 3;
  using M = std::uint64_t;
  const double ax = f.axis.x, ay = f.axis.y, az = f.axis.z;
  const double nx = f.normal.x, ny = f.normal.y, nz = f.normal.z;
  const double u0 = f.u0, u1 = f.u1, v0 = f.v0, v1 = f.v1, a0 = f.a0, a1 = f.a1;
  const double tip1 = f.tip1, tip2 = f.tip2, rise = f.rise, tol = f.linearTol;
  M count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const M covered = any[i] & ~apart[i] & M(a0 >= hlo[i]) & M(a1 <= hhi[i]);
    const M outside = M(us[i] < u0) | M(us[i] > u1) | M(vs[i] < v0) | M(vs[i] > v1);
    const M in = (outside | covered) ^ 1;
    keep[i] = in;
    count += in;
    double c[3];
    c[k1] = us[i] - tip1;
    c[k2] = vs[i] - tip2;
    c[kAxis] = 0.0;
    const double z = ax * c[0] + ay * c[1] + az * c[2];
    zeta[i] = z;
    h0[i] = nx * c[0] + ny * c[1] + nz * c[2];
    // The heights on the axis the line passes over s in [0, L].
    za[i] = std::min(z, z - rise) - tol;
    zb[i] = std::max(z, z - rise) + tol;
    lo[i] = HUGE_VAL;
    hi[i] = -HUGE_VAL;
  }
  return count;
}

// Lines [at, at + n) of the call (us and vs start at line `at` too).
MDHD_ROW_TARGETS bool bodyLines(int axis, const BodyFrame& f, const double* us, const double* vs,
                                std::size_t at, std::size_t n, CrossScratch& s) {
  const BodyFrame b = f;
  const auto run = [&](auto on) {
    return bodyLinesOn<decltype(on)::value>(
               b, us, vs, n, s.hulls.any.data() + at, s.hulls.apart.data() + at,
               s.hulls.lo.data() + at, s.hulls.hi.data() + at, s.keep.data() + at,
               s.zeta.data() + at, s.h0.data() + at, s.za.data() + at, s.zb.data() + at,
               s.lo.data() + at, s.hi.data() + at) > 0;
  };
  if (axis == 0) return run(std::integral_constant<int, 0>{});
  if (axis == 1) return run(std::integral_constant<int, 1>{});
  return run(std::integral_constant<int, 2>{});
}

// The body's lines that the piece may meet (crossBodyInterval's tests): on[i].
[[gnu::always_inline]] inline void pieceMask(const PieceFrame& p, const double* __restrict us,
                                             const double* __restrict vs, std::size_t n,
                                             const std::uint64_t* __restrict keep,
                                             const double* __restrict za,
                                             const double* __restrict zb,
                                             std::uint64_t* __restrict on) {
  using M = std::uint64_t;
  const double z0 = p.z0, z1 = p.z1, u0 = p.u0, u1 = p.u1, v0 = p.v0, v1 = p.v1;
  for (std::size_t i = 0; i < n; ++i)
    on[i] = keep[i] & ((M(z1 < za[i]) | M(z0 > zb[i]) | M(us[i] < u0) | M(us[i] > u1) |
                        M(vs[i] < v0) | M(vs[i] > v1)) ^
                       1);
}

// Those of lines [at, at + n) gathered into pz/ph with their indices (from `at`) in
// idx; returns how many.
MDHD_ROW_TARGETS std::size_t pieceLines(const PieceFrame& f, const double* us, const double* vs,
                                        std::size_t at, std::size_t n, CrossScratch& s) {
  pieceMask(f, us, vs, n, s.keep.data() + at, s.za.data() + at, s.zb.data() + at, s.on.data() + at);
  const double* zeta = s.zeta.data() + at;
  const double* h0 = s.h0.data() + at;
  const std::uint64_t* on = s.on.data() + at;
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    // Written always, kept where on: no branch.
    s.idx[k] = static_cast<std::uint32_t>(i);
    s.pz[k] = zeta[i];
    s.ph[k] = h0[i];
    k += on[i];
  }
  return k;
}

// Adds the body's interval on each of its lines (lo, hi relative to the tip's `tip`)
// to the line's hull (crossBodyInterval's result for every line the body holds).
MDHD_ROW_TARGETS void mergeBody(double tip, std::size_t at, std::size_t n, CrossScratch& s) {
  using M = std::uint64_t;
  const std::uint64_t* __restrict keep = s.keep.data() + at;
  const double* __restrict lo = s.lo.data() + at;
  const double* __restrict hi = s.hi.data() + at;
  const auto lane = [&](std::size_t i, double& ilo, double& ihi) {
    ilo = lo[i] + tip;
    ihi = hi[i] + tip;
    return keep[i] & M(hi[i] > lo[i]) & M(ihi > ilo);
  };
  Hulls& h = s.hulls;
  mergeLanes(n, lane, h.any.data() + at, h.apart.data() + at, h.lo.data() + at, h.hi.data() + at);
}

}  // namespace

void SweptVolume::rowIntervals(int axis, std::span<const double> us, double v,
                               std::vector<Interval>& out, std::span<std::size_t> ends) const {
  const std::size_t n = us.size();
  const bool meets =
      axis >= 0 && axis <= 2 && n > 0 &&
      !(v < coord(bounds_.lo, (axis + 2) % 3) || v > coord(bounds_.hi, (axis + 2) % 3));
  if (!meets) {
    std::fill(ends.begin(), ends.end(), out.size());
    return;
  }
  if (!rowKernel_[axis]) {
    if (rowCross_[axis]) {
      // Lines square to every body: the general form, all at this v.
      thread_local std::vector<double> vs;
      vs.assign(n, v);
      crossLinesIntervals(axis, us, vs, out, ends);
      return;
    }
    // Bodies off the lines' axis gain nothing body by body (and lose the skip of a
    // body inside what the line holds already, which turning moves live on).
    LineSolid::rowIntervals(axis, us, v, out, ends);
    return;
  }
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  struct Scratch {
    Hulls hulls;
    std::vector<double> q1, lo, hi;
    std::vector<unsigned char> hit;
  };
  thread_local Scratch s;
  s.hulls.reset(n);
  for (const SweptBody& body : bodies_) {
    if (v < coord(body.box.lo, i2) || v > coord(body.box.hi, i2)) continue;
    // The lines whose u the body's box holds (a line outside it misses the body).
    const std::size_t b = static_cast<std::size_t>(
        std::lower_bound(us.begin(), us.end(), coord(body.box.lo, i1)) - us.begin());
    const std::size_t e = static_cast<std::size_t>(
        std::upper_bound(us.begin() + b, us.end(), coord(body.box.hi, i1)) - us.begin());
    if (b >= e) continue;
    const std::size_t m = e - b;
    s.q1.resize(m), s.lo.resize(m), s.hi.resize(m), s.hit.resize(m);
    const double tip1 = coord(body.tip, i1);
    for (std::size_t j = 0; j < m; ++j) s.q1[j] = us[b + j] - tip1;
    axialExtentRow(profiles_[body.profile], body.along, s.q1.data(), v - coord(body.tip, i2), m,
                   body.linearTol, s.lo.data(), s.hi.data(), s.hit.data());
    // Heights run along the line with the axis' sign (axialInterval).
    mergeAxial(coord(body.tip, axis), coord(body.axis, axis) > 0.0, b, m, s.lo.data(), s.hi.data(),
               s.hit.data(), s.hulls);
  }
  s.hulls.emit(out, ends, [&](std::size_t i) { lineIntervals(axis, us[i], v, out); });
}

void SweptVolume::linesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                                 std::vector<Interval>& out, std::span<std::size_t> ends) const {
  if (axis >= 0 && axis <= 2 && rowCross_[axis]) {
    crossLinesIntervals(axis, us, vs, out, ends);
    return;
  }
  LineSolid::linesIntervals(axis, us, vs, out, ends);
}

void SweptVolume::crossLinesIntervals(int axis, std::span<const double> us,
                                      std::span<const double> vs, std::vector<Interval>& out,
                                      std::span<std::size_t> ends) const {
  // crossBodyInterval body by body, each loop over the lines without a branch per
  // line: the body's values for every line (bodyLines), then each piece over the
  // lines its tests keep (pieceLines, crossExtentRow), then the lines' unions.
  const std::size_t n = us.size();
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  thread_local CrossScratch s;
  s.reset(n);
  // Lines in rows (a cell asks them row by row) come sorted on one coordinate: a body
  // then only looks at the run of lines its box holds there (a short body of a long
  // chain, at most a few of the rows); the others it would mask out line by line.
  const bool byU = std::is_sorted(us.begin(), us.end());
  const bool byV = !byU && std::is_sorted(vs.begin(), vs.end());
  for (const SweptBody& body : bodies_) {
    const CrossMove& mv = body.cross[axis];
    const BodyFrame f{coord(body.box.lo, i1), coord(body.box.hi, i1),   coord(body.box.lo, i2),
                      coord(body.box.hi, i2), coord(body.box.lo, axis), coord(body.box.hi, axis),
                      coord(body.tip, i1),    coord(body.tip, i2),      body.axis,
                      body.crossNormal[axis], mv.length * mv.zd,        body.linearTol};
    std::size_t b = 0, e = n;
    if (byU || byV) {
      const std::span<const double> sorted = byU ? us : vs;
      const double lo = byU ? f.u0 : f.v0, hi = byU ? f.u1 : f.v1;
      b = static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), lo) -
                                   sorted.begin());
      e = static_cast<std::size_t>(std::upper_bound(sorted.begin() + b, sorted.end(), hi) -
                                   sorted.begin());
      if (b >= e) continue;
    }
    const std::size_t m = e - b;
    if (!bodyLines(axis, f, us.data() + b, vs.data() + b, b, m, s)) continue;
    for (int pi = body.pieceBegin; pi < body.pieceEnd; ++pi) {
      const SweptPiece& p = pieces_[pi];
      const PieceFrame pf{p.q.z0,
                          p.q.z1,
                          coord(p.box.lo, i1),
                          coord(p.box.hi, i1),
                          coord(p.box.lo, i2),
                          coord(p.box.hi, i2)};
      const std::size_t k = pieceLines(pf, us.data() + b, vs.data() + b, b, m, s);
      if (k == 0) continue;
      crossExtentRow(p.q, mv, s.pz.data(), s.ph.data(), k, body.linearTol, body.quadricTol,
                     s.plo.data(), s.phi.data(), s.hit.data());
      for (std::size_t t = 0; t < k; ++t) {
        const std::size_t j = b + s.idx[t];
        const bool on = s.hit[t];
        s.lo[j] = on ? std::min(s.lo[j], s.plo[t]) : s.lo[j];
        s.hi[j] = on ? std::max(s.hi[j], s.phi[t]) : s.hi[j];
      }
    }
    mergeBody(coord(body.tip, axis), b, m, s);
  }
  s.hulls.emit(out, ends, [&](std::size_t i) { lineIntervals(axis, us[i], vs[i], out); });
}

}  // namespace mdhd::geom

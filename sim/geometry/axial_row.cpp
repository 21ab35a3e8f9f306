// axialExtentRow: axialExtent over a row of lines, choices made by selection so
// that the loop has no branch per line and the compiler can vectorise it. This
// file is built with -O3 -fno-math-errno -fno-trapping-math (CMakeLists.txt): a
// square root of a negative number cannot happen here (every argument is clamped
// at 0), and neither errno nor traps may keep the selections from being made on
// whole vectors. Neither flag changes a result.
//
// The operations are axialExtent's, in its order, so every answer is the same to
// the bit (tests/geometry/test_row_intervals.cpp holds the two side by side).
#include <algorithm>
#include <cmath>

#include "sim/geometry/axial_sweep.h"
#include "sim/geometry/row_targets.h"

namespace mdhd::geom {

namespace {

// The profiles the kernel is specialised for: the rise loop and lowAt's search
// then cost nothing for the common tools.
enum class Rises { kNone, kSphere, kFrustum, kAny };

// What the loop reads of a profile, copied into locals: read through the profile
// (memory the loop's stores could alias, for all the compiler knows), every
// selection below would be a branch.
struct Shape {
  explicit Shape(const AxialProfile& p)
      : bottom(p.bottom),
        bottomRadiusSq(p.bottomRadiusSq),
        maxRadiusSq(p.maxRadiusSq),
        riseTop(p.riseTop),
        first(p.rises.empty() ? AxialProfile::Rise{} : p.rises[0]),
        all(p) {}
  double bottom, bottomRadiusSq, maxRadiusSq, riseTop;
  AxialProfile::Rise first;  // the only rise, for kSphere and kFrustum
  const AxialProfile& all;   // for kAny
};

// The lowest height of a rise-free profile, one sphere or one frustum, or any.
template <Rises R>
[[gnu::always_inline]] inline double lowAtSelect(const Shape& p, double rho2) {
  double z = p.riseTop;
  if constexpr (R == Rises::kSphere) {
    const AxialProfile::Rise& r = p.first;
    z = !(r.r1sq < rho2) ? r.centre - std::sqrt(std::max(0.0, r.radiusSq - rho2)) : z;
  } else if constexpr (R == Rises::kFrustum) {
    const AxialProfile::Rise& r = p.first;
    const double f = std::clamp(r.z0 + (std::sqrt(rho2) - r.r0) * r.slope, r.z0, r.z1);
    z = !(r.r1sq < rho2) ? f : z;
  } else if constexpr (R == Rises::kAny) {
    // The rises' top radii grow: the last (from the top down) whose top reaches
    // rho2 is the first that does, the one lowAt's search finds.
    for (std::size_t j = p.all.rises.size(); j-- > 0;) {
      const AxialProfile::Rise& r = p.all.rises[j];
      const double sphere = r.centre - std::sqrt(std::max(0.0, r.radiusSq - rho2));
      const double frustum = std::clamp(r.z0 + (std::sqrt(rho2) - r.r0) * r.slope, r.z0, r.z1);
      z = !(r.r1sq < rho2) ? (r.sphere ? sphere : frustum) : z;
    }
  }
  return rho2 <= p.bottomRadiusSq ? p.bottom : z;
}

// How far past the trace's nearest point the lowest point lies, as axialExtent's
// walk over the rises finds it (its `delta`).
template <Rises R>
[[gnu::always_inline]] inline double lowestDelta(const Shape& p, double k2, double a, double cross2,
                                                 double rhoMin2) {
  double delta = p.maxRadiusSq - rhoMin2;  // none: out to the widest radius
  bool found = false;
  auto rise = [&](const AxialProfile::Rise& r, bool sphere) {
    double ds = -1.0;
    if (sphere) {
      ds = k2 * r.radiusSq + cross2 <= r.r1sq * (a + k2) ? k2 * (r.radiusSq - rhoMin2) / (a + k2)
                                                         : -1.0;
    } else {
      const double den = a - k2 * r.k2;
      ds = ((den > 0.0) & (cross2 <= r.r1sq * den)) ? rhoMin2 * k2 * r.k2 / den : -1.0;
    }
    const bool take = !found & !(r.r1sq < rhoMin2) & (ds >= 0.0);
    delta = take ? std::max(ds, r.r0sq - rhoMin2) : delta;
    found = found | take;
  };
  if constexpr (R == Rises::kSphere) rise(p.first, true);
  if constexpr (R == Rises::kFrustum) rise(p.first, false);
  if constexpr (R == Rises::kAny)
    for (const AxialProfile::Rise& r : p.all.rises) {
      // Both forms, then the one of the rise's kind: no branch on it.
      const bool wasFound = found;
      const double before = delta;
      rise(r, true);
      const double asSphere = delta;
      const bool sphereFound = found;
      found = wasFound, delta = before;
      rise(r, false);
      delta = r.sphere ? asSphere : delta;
      found = r.sphere ? sphereFound : found;
    }
  return delta;
}

template <Rises R, bool kMoves>
[[gnu::always_inline]] inline void row(const AxialProfile& profile, const AxialMove& move,
                                       const double* __restrict q1, double q2, std::size_t n,
                                       double linearTol, double* __restrict lo,
                                       double* __restrict hi, unsigned char* __restrict hit) {
  const Shape shape(profile);
  const double top = profile.top;
  const double d1 = move.d1, d2 = move.d2;
  const double reach = profile.maxRadius + linearTol;
  const double reach2 = reach * reach;
  const double a = move.a;
  const double k = move.k;
  const double len = move.length;
  const double touchTol = linearTol / std::sqrt(a);
  const double k2 = k * k;
  for (std::size_t i = 0; i < n; ++i) {
    const double cross = q1[i] * d2 - q2 * d1;
    const double cross2 = cross * cross;
    const double rhoMin2 = cross2 / a;
    const bool near = !(rhoMin2 > reach2);
    const double sStar = (q1[i] * d1 + q2 * d2) / a;
    const double half = std::sqrt(std::max(0.0, shape.maxRadiusSq - rhoMin2) / a);
    double sLo = std::max(0.0, sStar - half);
    double sHi = std::min(len, sStar + half);
    // Touching the wall at one end of the move, within the tolerance.
    const bool apart = sLo > sHi;
    const bool touches = !(sLo > sHi + touchTol);
    const double mid = 0.5 * (sLo + sHi);
    sLo = apart ? mid : sLo;
    sHi = apart ? mid : sHi;
    double sm = sStar;
    if constexpr (kMoves) {
      const double delta = lowestDelta<R>(shape, k2, a, cross2, rhoMin2);
      sm = sStar - std::copysign(std::sqrt(std::max(0.0, delta) / a), k);
    }
    const double sc = std::clamp(sm, sLo, sHi);
    const double e1 = q1[i] - sc * d1;
    const double e2 = q2 - sc * d2;
    const double l = k * sc + lowAtSelect<R>(shape, std::min(e1 * e1 + e2 * e2, shape.maxRadiusSq));
    const double h = top + std::max(k * sLo, k * sHi);
    lo[i] = l;
    hi[i] = h;
    hit[i] = near & touches & (h > l);
  }
}

template <Rises R>
[[gnu::always_inline]] inline void rowOf(const AxialProfile& profile, const AxialMove& move,
                                         const double* __restrict q1, double q2, std::size_t n,
                                         double linearTol, double* __restrict lo,
                                         double* __restrict hi, unsigned char* __restrict hit) {
  const double len = move.length;
  if (move.a * len * len <= 1e-24 * (1.0 + len * len)) {
    // Nothing moves across the axis (a plunge, a stamp): one chord, shifted.
    const double reach = profile.maxRadius + linearTol;
    const double reach2 = reach * reach;
    const double shift = std::min(0.0, move.k * len);
    const double top = profile.top + std::max(0.0, move.k * len);
    const Shape shape(profile);
    for (std::size_t i = 0; i < n; ++i) {
      const double rho2 = q1[i] * q1[i] + q2 * q2;
      const double l = lowAtSelect<R>(shape, std::min(rho2, shape.maxRadiusSq)) + shift;
      lo[i] = l;
      hi[i] = top;
      hit[i] = !(rho2 > reach2) & (top > l);
    }
    return;
  }
  if (move.k != 0.0)
    row<R, true>(profile, move, q1, q2, n, linearTol, lo, hi, hit);
  else
    row<R, false>(profile, move, q1, q2, n, linearTol, lo, hi, hit);
}

}  // namespace

MDHD_ROW_TARGETS void axialExtentRow(const AxialProfile& profile, const AxialMove& move,
                                     const double* q1, double q2, std::size_t n, double linearTol,
                                     double* lo, double* hi, unsigned char* hit) {
  if (profile.rises.empty())
    rowOf<Rises::kNone>(profile, move, q1, q2, n, linearTol, lo, hi, hit);
  else if (profile.rises.size() == 1 && profile.rises[0].sphere)
    rowOf<Rises::kSphere>(profile, move, q1, q2, n, linearTol, lo, hi, hit);
  else if (profile.rises.size() == 1)
    rowOf<Rises::kFrustum>(profile, move, q1, q2, n, linearTol, lo, hi, hit);
  else
    rowOf<Rises::kAny>(profile, move, q1, q2, n, linearTol, lo, hi, hit);
}

}  // namespace mdhd::geom

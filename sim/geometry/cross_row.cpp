// crossExtentRow: crossExtent over many lines along one axis (each with its own height
// on the tool's axis and distance across the move: the x or y lines of a z map at
// many levels and rows), choices made by selection so that the loop can be
// vectorised. Built like axial_row.cpp (-O3, no errno, no traps; CMakeLists.txt).
//
// The operations are crossExtent's, in its order, and a candidate end enters the
// extent exactly where crossExtent's would (min and max see the same values in the
// same order, so even a tie of -0 and +0 comes out the same): the answers are the
// same to the bit.
#include <algorithm>
#include <cmath>

#include "sim/geometry/cross_sweep.h"
#include "sim/geometry/row_targets.h"

namespace mdhd::geom {

namespace {

// The running extent; add(t) only where `on`.
struct Extent {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  [[gnu::always_inline]] void add(bool on, double t) {
    lo = on ? std::min(lo, t) : lo;
    hi = on ? std::max(hi, t) : hi;
  }
};

// The s range of the line's height in the piece's, within [0, L]; `miss` when none.
[[gnu::always_inline]] inline void heightRange(const PieceQuadric& p, const CrossMove& m,
                                               double zeta0, double linearTol, double& s0,
                                               double& s1, bool& miss) {
  // Both cases computed, the move's chosen (m.zd is the same for the whole row).
  const bool level = m.zd == 0.0;
  const bool outside = (zeta0 < p.z0 - linearTol) | (zeta0 > p.z1 + linearTol);
  const double a = (zeta0 - p.z1) / m.zd;
  const double b = (zeta0 - p.z0) / m.zd;
  double r0 = std::max(0.0, std::min(a, b));
  double r1 = std::min(m.length, std::max(a, b));
  const bool apart = r0 > r1;
  const bool far = apart & (r0 > r1 + linearTol);
  const double mid = 0.5 * (r0 + r1);
  r0 = apart ? mid : r0;
  r1 = apart ? mid : r1;
  s0 = level ? 0.0 : r0;
  s1 = level ? m.length : r1;
  miss = (level & outside) | (!level & far);
}

[[gnu::always_inline]] inline void stadiumRow(const PieceQuadric& p, const CrossMove& m,
                                              const double* __restrict zeta0,
                                              const double* __restrict h0, std::size_t n,
                                              double linearTol, double quadricTol,
                                              double* __restrict lo, double* __restrict hi,
                                              unsigned char* __restrict hit) {
  const double r2 = p.alpha;
  // The sides: the centres' track offset by +-R along its normal (-dn, de) / planar;
  // crossExtent's products, hoisted where they do not depend on the line.
  const bool sidesExist = m.dn != 0.0;
  const double r = std::sqrt(r2);
  double acrossS[2], alongT[2];
  for (int j = 0; j < 2; ++j) {
    const double sign = j == 0 ? 1.0 : -1.0;
    acrossS[j] = sign * r * m.de / m.planar;
    alongT[j] = sign * r * m.dn / m.planar;
  }
  for (std::size_t i = 0; i < n; ++i) {
    double s0, s1;
    bool miss;
    heightRange(p, m, zeta0[i], linearTol, s0, s1, miss);
    const double h = h0[i];
    Extent e;
    const bool trySides = sidesExist & (s1 > s0);
    const double sideS0 = (h - acrossS[0]) / m.dn, sideS1 = (h - acrossS[1]) / m.dn;
    const bool side0 = trySides & (sideS0 >= s0) & (sideS0 <= s1);
    const bool side1 = trySides & (sideS1 >= s0) & (sideS1 <= s1);
    e.add(side0, sideS0 * m.de - alongT[0]);
    e.add(side1, sideS1 * m.de - alongT[1]);
    // The end circles (a line crosses a convex set's boundary twice: two sides are all).
    const bool ends = !(side0 & side1);
    for (int j = 0; j < 2; ++j) {
      const double s = j == 0 ? s0 : s1;
      const double g = s * m.dn - h;
      const double q = r2 - g * g;
      const double w = std::sqrt(std::max(0.0, q));
      const bool on = ends & !(q < -quadricTol);
      e.lo = on ? std::min(e.lo, s * m.de - w) : e.lo;
      e.hi = on ? std::max(e.hi, s * m.de + w) : e.hi;
    }
    lo[i] = e.lo;
    hi[i] = e.hi;
    hit[i] = !miss & (e.lo <= e.hi);
  }
}

// One turning point of a chord end at s (crossExtent's `turn`), entered where valid.
// kAcross: the move has no component along the line (de == 0).
template <bool kAcross>
[[gnu::always_inline]] inline void turnAt(bool valid, double s, double s0, double s1, double q2,
                                          double q1, double q0, const CrossMove& m,
                                          double linearTol, double quadricTol, Extent& e) {
  const bool inside = (s >= s0 - linearTol) & (s <= s1 + linearTol);
  s = std::clamp(s, s0, s1);
  const double qs = (q2 * s + q1) * s + q0;
  if constexpr (kAcross) {
    const double r = std::sqrt(std::max(0.0, qs));
    const bool on = valid & inside & !(qs < -quadricTol);
    e.add(on, -r);
    e.add(on, r);
  } else {
    const double tau = -(2.0 * q2 * s + q1) / (2.0 * m.de);
    const bool onQ = !(std::abs(tau * tau - qs) > 1e-6 * (std::abs(qs) + tau * tau) + quadricTol);
    e.add(valid & inside & onQ, s * m.de + tau);
  }
}

template <bool kAcross>
[[gnu::always_inline]] inline void quadricRow(const PieceQuadric& p, const CrossMove& m,
                                              const double* __restrict zeta0,
                                              const double* __restrict h0s, std::size_t n,
                                              double linearTol, double quadricTol,
                                              double* __restrict lo, double* __restrict hi,
                                              unsigned char* __restrict hit) {
  const double zd = m.zd, dn = m.dn, de = m.de;
  const double q2 = p.gamma * zd * zd - dn * dn;
  for (std::size_t i = 0; i < n; ++i) {
    const double z = zeta0[i], h0 = h0s[i];
    double s0, s1;
    bool miss;
    heightRange(p, m, z, linearTol, s0, s1, miss);
    const double q1 = -zd * (p.beta + 2.0 * p.gamma * z) + 2.0 * h0 * dn;
    const double q0 = p.alpha + (p.beta + p.gamma * z) * z - h0 * h0;
    Extent e;
    for (int j = 0; j < 2; ++j) {
      const double s = j == 0 ? s0 : s1;
      const double qs = (q2 * s + q1) * s + q0;
      const double r = std::sqrt(std::max(0.0, qs));
      // crossExtent stops after the first end when the range is one point.
      const bool on = !(qs < -quadricTol) & !(j == 1 && s1 == s0);
      e.add(on, s * de - r);
      e.add(on, s * de + r);
    }
    if constexpr (kAcross) {
      turnAt<true>(q2 != 0.0, -q1 / (2.0 * q2), s0, s1, q2, q1, q0, m, linearTol, quadricTol, e);
    } else {
      const double de2 = de * de;
      const double c2 = 4.0 * q2 * (q2 - de2);
      const double c1 = 4.0 * q1 * (q2 - de2);
      const double c0 = q1 * q1 - 4.0 * de2 * q0;
      const bool quadratic = std::abs(c2) > 1e-14 * (std::abs(c1) + std::abs(c0));
      const double disc0 = c1 * c1 - 4.0 * c2 * c0;
      // A discriminant just below 0 by rounding is 0 (one masks each, no select of masks).
      const bool snap = (disc0 < 0.0) & (disc0 >= -1e-12 * (c1 * c1 + std::abs(4.0 * c2 * c0)));
      const double disc = snap ? 0.0 : disc0;
      const bool roots = quadratic & ((disc0 >= 0.0) | snap);
      const double r = -0.5 * (c1 + std::copysign(std::sqrt(std::max(0.0, disc)), c1));
      const bool two = roots & (r != 0.0);
      turnAt<false>(two, r / c2, s0, s1, q2, q1, q0, m, linearTol, quadricTol, e);
      turnAt<false>(two, c0 / r, s0, s1, q2, q1, q0, m, linearTol, quadricTol, e);
      turnAt<false>(roots & !(r != 0.0), 0.0, s0, s1, q2, q1, q0, m, linearTol, quadricTol, e);
      turnAt<false>(!quadratic & (c1 != 0.0), -c0 / c1, s0, s1, q2, q1, q0, m, linearTol,
                    quadricTol, e);
    }
    lo[i] = e.lo;
    hi[i] = e.hi;
    hit[i] = !miss & (e.lo <= e.hi);
  }
}

}  // namespace

MDHD_ROW_TARGETS void crossExtentRow(const PieceQuadric& p, const CrossMove& m, const double* zeta0,
                                     const double* h0, std::size_t n, double linearTol,
                                     double quadricTol, double* lo, double* hi,
                                     unsigned char* hit) {
  // Copies: read through the references, every field would be loaded again after
  // each store (the compiler cannot tell they do not alias), and the loop stay scalar.
  const PieceQuadric piece = p;
  const CrossMove move = m;
  if (piece.gamma == 0.0 && piece.beta == 0.0)
    stadiumRow(piece, move, zeta0, h0, n, linearTol, quadricTol, lo, hi, hit);
  else if (move.de == 0.0)
    quadricRow<true>(piece, move, zeta0, h0, n, linearTol, quadricTol, lo, hi, hit);
  else
    quadricRow<false>(piece, move, zeta0, h0, n, linearTol, quadricTol, lo, hi, hit);
}

}  // namespace mdhd::geom

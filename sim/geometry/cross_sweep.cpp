#include "sim/geometry/cross_sweep.h"

#include <algorithm>
#include <cmath>

namespace mdhd::geom {

namespace {

// The disks of squared radius r2 centred at (s de, s dn - h0) (along the line, across
// it) for s in [s0, s1]: the chord of their union, the stadium, on the line.
bool stadiumExtent(double r2, const CrossMove& m, double h0, double s0, double s1,
                   double quadricTol, double& lo, double& hi) {
  double tlo = HUGE_VAL;
  double thi = -HUGE_VAL;
  int sides = 0;
  if (m.dn != 0.0 && s1 > s0) {
    // The sides: the centres' track offset by +-R along its normal (-dn, de) / planar.
    const double r = std::sqrt(r2);
    for (const double sign : {1.0, -1.0}) {
      const double s = (h0 - sign * r * m.de / m.planar) / m.dn;
      if (!(s >= s0 && s <= s1)) continue;
      const double t = s * m.de - sign * r * m.dn / m.planar;
      tlo = std::min(tlo, t);
      thi = std::max(thi, t);
      ++sides;
    }
  }
  if (sides < 2) {
    // The end circles (a line crosses a convex set's boundary twice: two sides are all).
    for (const double s : {s0, s1}) {
      const double g = s * m.dn - h0;
      const double q = r2 - g * g;
      if (q < -quadricTol) continue;
      const double w = std::sqrt(std::max(0.0, q));
      tlo = std::min(tlo, s * m.de - w);
      thi = std::max(thi, s * m.de + w);
    }
  }
  if (!(tlo <= thi)) return false;
  lo = tlo;
  hi = thi;
  return true;
}

}  // namespace

bool crossExtent(const PieceQuadric& p, const CrossMove& m, double zeta0, double h0,
                 double linearTol, double quadricTol, double& lo, double& hi) {
  // The s for which the line's height lies in the piece's, within [0, L].
  double s0 = 0.0;
  double s1 = m.length;
  if (m.zd == 0.0) {
    if (zeta0 < p.z0 - linearTol || zeta0 > p.z1 + linearTol) return false;
  } else {
    const double a = (zeta0 - p.z1) / m.zd;
    const double b = (zeta0 - p.z0) / m.zd;
    s0 = std::max(s0, std::min(a, b));
    s1 = std::min(s1, std::max(a, b));
    if (s0 > s1) {
      if (s0 > s1 + linearTol) return false;
      s0 = s1 = 0.5 * (s0 + s1);
    }
  }
  if (p.gamma == 0.0 && p.beta == 0.0)
    return stadiumExtent(p.alpha, m, h0, s0, s1, quadricTol, lo, hi);
  // Q(s) = q2 s^2 + q1 s + q0
  const double zd = m.zd, dn = m.dn, de = m.de;
  const double q2 = p.gamma * zd * zd - dn * dn;
  const double q1 = -zd * (p.beta + 2.0 * p.gamma * zeta0) + 2.0 * h0 * dn;
  const double q0 = p.alpha + (p.beta + p.gamma * zeta0) * zeta0 - h0 * h0;
  auto q = [&](double s) { return (q2 * s + q1) * s + q0; };
  double tlo = HUGE_VAL;
  double thi = -HUGE_VAL;
  auto add = [&](double t) {
    tlo = std::min(tlo, t);
    thi = std::max(thi, t);
  };
  for (const double s : {s0, s1}) {
    const double qs = q(s);
    if (qs < -quadricTol) continue;
    const double r = std::sqrt(std::max(0.0, qs));
    add(s * de - r);
    add(s * de + r);
    if (s1 == s0) break;
  }
  // Where a chord end turns: d/ds (s de +- sqrt(Q)) = 0, i.e. Q'^2 = 4 de^2 Q.
  auto turn = [&](double s) {
    if (!(s >= s0 - linearTol && s <= s1 + linearTol)) return;
    s = std::clamp(s, s0, s1);
    const double qs = q(s);
    if (de == 0.0) {
      if (qs < -quadricTol) return;
      const double r = std::sqrt(std::max(0.0, qs));
      add(-r);
      add(r);
      return;
    }
    const double tau = -(2.0 * q2 * s + q1) / (2.0 * de);
    // A root of a nearly degenerate quadratic may be rounding alone: it must lie on Q.
    if (std::abs(tau * tau - qs) > 1e-6 * (std::abs(qs) + tau * tau) + quadricTol) return;
    add(s * de + tau);
  };
  if (de == 0.0) {
    if (q2 != 0.0) turn(-q1 / (2.0 * q2));
  } else {
    const double de2 = de * de;
    const double c2 = 4.0 * q2 * (q2 - de2);
    const double c1 = 4.0 * q1 * (q2 - de2);
    const double c0 = q1 * q1 - 4.0 * de2 * q0;
    if (std::abs(c2) > 1e-14 * (std::abs(c1) + std::abs(c0))) {
      double disc = c1 * c1 - 4.0 * c2 * c0;
      if (disc < 0.0 && disc >= -1e-12 * (c1 * c1 + std::abs(4.0 * c2 * c0))) disc = 0.0;
      if (disc >= 0.0) {
        const double r = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
        if (r != 0.0) {
          turn(r / c2);
          turn(c0 / r);
        } else {
          turn(0.0);
        }
      }
    } else if (c1 != 0.0) {
      turn(-c0 / c1);
    }
  }
  if (!(tlo <= thi)) return false;
  lo = tlo;
  hi = thi;
  return true;
}

}  // namespace mdhd::geom

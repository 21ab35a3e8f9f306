#include "sim/geometry/capsule_line.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mdhd::geom {

namespace {

// t where |p + t e| <= r around a centre at p = me, pp from the line's origin.
bool sphereSpan(double pe, double pp, double r, double& lo, double& hi) {
  const double disc = pe * pe - (pp - r * r);
  if (!(disc > 0.0)) return false;
  const double root = std::sqrt(disc);
  lo = -pe - root;
  hi = -pe + root;
  return true;
}

}  // namespace

bool capsuleExtent(double me, double md, double mm, double ed, double length, double radius,
                   double& lo, double& hi) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  double l = inf, h = -inf;
  const auto take = [&](double a, double b) {
    l = std::min(l, a);
    h = std::max(h, b);
  };
  double a = 0.0, b = 0.0;
  // The balls at both ends.
  if (sphereSpan(me, mm, radius, a, b)) take(a, b);
  if (length > 0.0) {
    const double me1 = me - length * ed, mm1 = mm - 2.0 * length * md + length * length;
    if (sphereSpan(me1, mm1, radius, a, b)) take(a, b);
    // The cylinder about the segment, where the foot of the point lies on the segment:
    // components square to d are e - ed d and m - md d.
    const double qa = 1.0 - ed * ed, qb = me - md * ed, qc = mm - md * md - radius * radius;
    double c0 = -inf, c1 = inf;
    bool inside = true;
    if (qa > 1e-12) {
      const double disc = qb * qb - qa * qc;
      inside = disc > 0.0;
      if (inside) {
        const double root = std::sqrt(disc);
        c0 = (-qb - root) / qa;
        c1 = (-qb + root) / qa;
      }
    } else {
      inside = qc < 0.0;  // along the segment: in or out of the cylinder everywhere
    }
    if (inside) {
      // md + t ed in [0, length].
      if (std::abs(ed) > 1e-300) {
        const double ta = -md / ed, tb = (length - md) / ed;
        c0 = std::max(c0, std::min(ta, tb));
        c1 = std::min(c1, std::max(ta, tb));
      } else if (md < 0.0 || md > length) {
        c1 = -inf;
      }
      if (c1 > c0) take(c0, c1);
    }
  }
  if (!(h > l)) return false;
  lo = l;
  hi = h;
  return true;
}

}  // namespace mdhd::geom

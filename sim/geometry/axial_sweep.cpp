#include "sim/geometry/axial_sweep.h"

#include <algorithm>
#include <cmath>

namespace mdhd::geom {

namespace {

// Pieces that should join, or a slope that should not grow, may differ by rounding.
constexpr double kJoin = 1e-9;

// d rho / d z at height z of a rising piece (infinite at a sphere's pole).
double slopeAt(const RevolvedPiece& p, double z) {
  if (p.sphere) {
    const double r = p.radiusAt(z);
    return r > 0.0 ? (p.centre - z) / r : HUGE_VAL;
  }
  return (p.r1 - p.r0) / (p.z1 - p.z0);
}

// A frustum's alpha, beta, gamma as frustumPiece makes them from r0, r1.
bool isFrustum(const RevolvedPiece& p) {
  const double k = (p.r1 - p.r0) / (p.z1 - p.z0);
  const double m = p.r0 - k * p.z0;
  const double scale = m * m + std::abs(2.0 * m * k) + k * k + 1.0;
  return std::abs(p.alpha - m * m) <= kJoin * scale &&
         std::abs(p.beta - 2.0 * m * k) <= kJoin * scale &&
         std::abs(p.gamma - k * k) <= kJoin * scale && m + k * p.z0 >= 0.0 && m + k * p.z1 >= 0.0;
}

}  // namespace

std::optional<AxialProfile> axialProfile(const ConvexBody& body) {
  if (body.pieces.empty()) return std::nullopt;
  AxialProfile out;
  out.bottom = body.bottom();
  out.top = body.top();
  const double scale = 1.0 + std::abs(out.bottom) + std::abs(out.top);
  double lastSlope = HUGE_VAL;
  bool flat = false;  // a piece of constant radius came: nothing may rise after it
  for (std::size_t i = 0; i < body.pieces.size(); ++i) {
    const RevolvedPiece& p = body.pieces[i];
    if (!(p.z1 > p.z0) || !std::isfinite(p.z0) || !std::isfinite(p.z1)) return std::nullopt;
    if (p.sphere ? p.z1 > p.centre + kJoin * scale : !isFrustum(p)) return std::nullopt;
    const double r0 = p.radiusAt(p.z0);
    const double r1 = p.radiusAt(p.z1);
    if (i > 0) {
      const RevolvedPiece& q = body.pieces[i - 1];
      if (std::abs(q.z1 - p.z0) > kJoin * scale) return std::nullopt;
      if (std::abs(q.radiusAt(q.z1) - r0) > kJoin * scale) return std::nullopt;
    } else {
      out.bottomRadiusSq = r0 * r0;
    }
    if (r1 < r0) return std::nullopt;
    if (r1 == r0) {
      flat = true;
      continue;
    }
    // Convex: the radius grows ever slower; a rise after a flat part is a dent.
    if (flat || slopeAt(p, p.z0) > lastSlope * (1.0 + kJoin) + kJoin) return std::nullopt;
    lastSlope = slopeAt(p, p.z1);
    AxialProfile::Rise r;
    r.r0 = r0;
    r.r1 = r1;
    r.r0sq = r0 * r0;
    r.r1sq = r1 * r1;
    r.z0 = p.z0;
    r.z1 = p.z1;
    r.sphere = p.sphere;
    if (p.sphere) {
      r.centre = p.centre;
      r.radiusSq = p.alpha + p.beta * p.centre + p.gamma * p.centre * p.centre;
    } else {
      const double k = (r1 - r0) / (p.z1 - p.z0);
      r.slope = 1.0 / k;
      r.k2 = k * k;
    }
    out.rises.push_back(r);
  }
  const RevolvedPiece& last = body.pieces.back();
  out.maxRadius = last.radiusAt(last.z1);
  out.maxRadiusSq = out.maxRadius * out.maxRadius;
  out.riseTop = out.rises.empty() ? out.bottom : out.rises.back().z1;
  return out;
}

double AxialProfile::lowAt(double rho2) const {
  if (rho2 <= bottomRadiusSq) return bottom;
  // The first rise that reaches rho2 (few pieces but the bull's corner: search).
  std::size_t lo = 0, hi = rises.size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (rises[mid].r1sq < rho2)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == rises.size()) return riseTop;
  const Rise& r = rises[lo];
  if (r.sphere) return r.centre - std::sqrt(std::max(0.0, r.radiusSq - rho2));
  return std::clamp(r.z0 + (std::sqrt(rho2) - r.r0) * r.slope, r.z0, r.z1);
}

bool axialExtent(const AxialProfile& profile, const AxialMove& move, double q1, double q2,
                 double linearTol, double& lo, double& hi) {
  // A line that touches the widest radius within the tolerance runs along the wall.
  const double reach = profile.maxRadius + linearTol;
  const double reach2 = reach * reach;
  const double a = move.a;
  const double k = move.k;
  const double len = move.length;
  if (a * len * len <= 1e-24 * (1.0 + len * len)) {
    // Nothing moves across the axis (a plunge, a stamp): one chord, shifted.
    const double rho2 = q1 * q1 + q2 * q2;
    if (rho2 > reach2) return false;
    lo = profile.lowAt(std::min(rho2, profile.maxRadiusSq)) + std::min(0.0, k * len);
    hi = profile.top + std::max(0.0, k * len);
    return hi > lo;
  }
  // rho(s)^2 = rhoMin2 + a (s - sStar)^2
  const double cross = q1 * move.d2 - q2 * move.d1;
  const double cross2 = cross * cross;
  const double rhoMin2 = cross2 / a;
  if (rhoMin2 > reach2) return false;
  const double sStar = (q1 * move.d1 + q2 * move.d2) / a;
  const double half = std::sqrt(std::max(0.0, profile.maxRadiusSq - rhoMin2) / a);
  double sLo = std::max(0.0, sStar - half);
  double sHi = std::min(len, sStar + half);
  if (sLo > sHi) {
    // Touching the wall at one end of the move, within the tolerance.
    if (sLo > sHi + linearTol / std::sqrt(a)) return false;
    sLo = sHi = 0.5 * (sLo + sHi);
  }
  // The lowest point: zLow(rho(s)) + k s is convex in s; on the side k points away
  // from, rho grows with |s - sStar|. Walk the rises outwards to the first whose own
  // stationary radius lies below its top (or at its start: a kink between pieces).
  double sm = sStar;
  if (k != 0.0) {
    const double k2 = k * k;
    double delta = profile.maxRadiusSq - rhoMin2;  // none: out to the widest radius
    for (const AxialProfile::Rise& r : profile.rises) {
      if (r.r1sq < rhoMin2) continue;
      double ds = -1.0;
      if (r.sphere) {
        // zLow = c - sqrt(R^2 - rho^2): rho*^2 = (k^2 R^2 + a rhoMin2) / (a + k^2)
        if (k2 * r.radiusSq + cross2 <= r.r1sq * (a + k2))
          ds = k2 * (r.radiusSq - rhoMin2) / (a + k2);
      } else {
        // zLow linear in rho with slope 1/kf: rho*^2 = a rhoMin2 / (a - k^2 kf^2)
        const double den = a - k2 * r.k2;
        if (den > 0.0 && cross2 <= r.r1sq * den) ds = rhoMin2 * k2 * r.k2 / den;
      }
      if (ds >= 0.0) {
        delta = std::max(ds, r.r0sq - rhoMin2);
        break;
      }
    }
    sm = sStar - std::copysign(std::sqrt(std::max(0.0, delta) / a), k);
  }
  const double sc = std::clamp(sm, sLo, sHi);
  const double e1 = q1 - sc * move.d1;
  const double e2 = q2 - sc * move.d2;
  lo = k * sc + profile.lowAt(std::min(e1 * e1 + e2 * e2, profile.maxRadiusSq));
  hi = profile.top + std::max(k * sLo, k * sHi);
  return hi > lo;
}

}  // namespace mdhd::geom

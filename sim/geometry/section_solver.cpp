#include "sim/geometry/section_solver.h"

#include <cmath>
#include <initializer_list>
#include <limits>

namespace mdhd::geom {

namespace {

constexpr double kTiny = 1e-13;

struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double t) {
    lo = t < lo ? t : lo;
    hi = t > hi ? t : hi;
  }
};

bool inHalfPlanes(const HalfPlane (&h)[4], const bool (&live)[4], double t, double s, double eps) {
  for (int i = 0; i < 4; ++i)
    if (live[i] && h[i](t, s) > eps) return false;
  return true;
}

// Real roots of A x^2 + 2 B x + C = 0, linear when |A| <= zeroA (a tangent whose
// discriminant rounding made negative still touches); none when it is constant.
[[gnu::always_inline]] inline int roots(double A, double B, double C, double zeroA,
                                        double (&x)[2]) {
  if (std::abs(A) <= zeroA) {
    if (B == 0.0) return 0;
    x[0] = -C / (2.0 * B);
    return 1;
  }
  double disc = B * B - A * C;
  if (disc < 0.0) {
    if (disc < -1e-12 * (B * B + std::abs(A * C))) return 0;
    disc = 0.0;
  }
  const double q = -(B + std::copysign(std::sqrt(disc), B));
  if (q == 0.0) {
    x[0] = 0.0;
    return 1;
  }
  x[0] = q / A;
  x[1] = C / q;
  return 2;
}

// Parameters lambda where g(p + lambda v) = 0, v a unit vector: 0, 1 or 2 of them (none
// when g is constant along the line: vertices decide).
int lineRoots(const Quadric2& g, double pt, double ps, double vt, double vs, double (&lam)[2]) {
  const double a2 = g.a * vt * vt + 2.0 * g.b * vt * vs + g.c * vs * vs;
  const double b2 = vt * (g.a * pt + g.b * ps + g.d) + vs * (g.b * pt + g.c * ps + g.e);
  return roots(a2, b2, g(pt, ps), kTiny, lam);
}

// The points of g = 0 on the line n . (t, s) + k = 0 that lie in the half-planes.
void addLineCandidates(const Quadric2& g, double nt, double ns, double k, const HalfPlane (&h)[4],
                       const bool (&live)[4], double eps, Extent& ext) {
  const double n2 = nt * nt + ns * ns;
  if (n2 <= kTiny * kTiny) return;
  const double len = n2 == 1.0 ? 1.0 : std::sqrt(n2);
  const double pt = -k * nt / n2;
  const double ps = -k * ns / n2;
  const double vt = -ns / len;
  const double vs = nt / len;
  double lam[2];
  const int n = lineRoots(g, pt, ps, vt, vs, lam);
  for (int i = 0; i < n; ++i) {
    const double t = pt + lam[i] * vt;
    const double s = ps + lam[i] * vs;
    if (inHalfPlanes(h, live, t, s, eps)) ext.add(t);
  }
}

void addVertexCandidates(const Quadric2& g, const HalfPlane (&h)[4], const bool (&live)[4],
                         const SectionTolerance& tol, Extent& ext) {
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      if (!live[i] || !live[j]) continue;
      const double det = h[i].nt * h[j].ns - h[i].ns * h[j].nt;
      const double scale2 =
          (h[i].nt * h[i].nt + h[i].ns * h[i].ns) * (h[j].nt * h[j].nt + h[j].ns * h[j].ns);
      if (det * det <= 1e-24 * scale2) continue;  // parallel edges never meet
      const double t = (-h[i].k * h[j].ns + h[j].k * h[i].ns) / det;
      const double s = (-h[j].k * h[i].nt + h[i].k * h[j].nt) / det;
      if (g(t, s) <= tol.quadric && inHalfPlanes(h, live, t, s, tol.linear)) ext.add(t);
    }
}

// A singular point of g on its zero set (the apex of a cone cut through its tip).
void addStationaryCandidate(const Quadric2& g, const HalfPlane (&h)[4], const bool (&live)[4],
                            const SectionTolerance& tol, Extent& ext) {
  const double det = g.a * g.c - g.b * g.b;
  if (det > 0.0 && g.a > 0.0) return;  // an ellipse's centre is inside, never an extreme
  if (std::abs(det) <= 1e-12 * (g.a * g.a + 2.0 * g.b * g.b + g.c * g.c)) return;
  const double t = (-g.d * g.c + g.e * g.b) / det;
  const double s = (-g.e * g.a + g.d * g.b) / det;
  if (g(t, s) <= tol.quadric && inHalfPlanes(h, live, t, s, tol.linear)) ext.add(t);
}

}  // namespace

bool sectionExtent(const Quadric2& g, const HalfPlane (&h)[4], const SectionTolerance& tol,
                   double& lo, double& hi) {
  // A half-plane without a normal is all or nothing.
  bool live[4];
  for (int i = 0; i < 4; ++i) {
    live[i] = h[i].nt * h[i].nt + h[i].ns * h[i].ns > kTiny * kTiny;
    if (!live[i] && h[i].k > tol.linear) return false;
  }
  Extent ext;
  addVertexCandidates(g, h, live, tol, ext);
  for (int i = 0; i < 4; ++i)
    if (live[i]) addLineCandidates(g, h[i].nt, h[i].ns, h[i].k, h, live, tol.linear, ext);
  addLineCandidates(g, g.b, g.c, g.e, h, live, tol.linear, ext);  // dg/ds = 0
  addStationaryCandidate(g, h, live, tol, ext);
  if (!(ext.lo <= ext.hi)) return false;
  lo = ext.lo;
  hi = ext.hi;
  return true;
}

namespace {

// roots() with a leading coefficient that is zero relative to the others.
[[gnu::always_inline]] inline int bandRoots(double A, double B, double C, double (&x)[2]) {
  return roots(A, B, C, kTiny * (std::abs(B) + std::abs(C)), x);
}

}  // namespace

bool bandExtent(const Quadric2& g, const Band& band, const SectionTolerance& tol, double& lo,
                double& hi) {
  const double L = band.length;
  const double ze = band.ze;
  const double zd = band.zd;
  const double eps = tol.linear;
  auto inS = [&](double s) { return s >= -eps && s <= L + eps; };
  auto inZ = [&](double t, double s) {
    const double z = band.zeta0 + ze * t - zd * s;
    return z >= band.z0 - eps && z <= band.z1 + eps;
  };
  Extent ext;
  const double ends[2] = {0.0, L};
  const double slab[2] = {band.z0, band.z1};
  // Corners.
  const bool open[2] = {band.open0, band.open1};
  for (const double s : ends)
    for (int k = 0; k < 2; ++k) {
      if (open[k]) continue;
      const double z = slab[k];
      const double t = (z - band.zeta0 + zd * s) / ze;
      if (g(t, s) <= tol.quadric) ext.add(t);
    }
  double x[2];
  // The edges s = 0 and s = L: g(t, s) = a t^2 + 2 (b s + d) t + (c s^2 + 2 e s + f).
  for (const double s : ends) {
    const int n = bandRoots(g.a, g.b * s + g.d, (g.c * s + 2.0 * g.e) * s + g.f, x);
    for (int i = 0; i < n; ++i)
      if (inZ(x[i], s)) ext.add(x[i]);
  }
  // The slab's edges: t = tau + mu s.
  const double mu = zd / ze;
  for (int k = 0; k < 2; ++k) {
    if (open[k]) continue;
    const double z = slab[k];
    const double tau = (z - band.zeta0) / ze;
    const double A = (g.a * mu + 2.0 * g.b) * mu + g.c;
    const double B = g.a * tau * mu + g.b * tau + g.d * mu + g.e;
    const double C = (g.a * tau + 2.0 * g.d) * tau + g.f;
    const int n = bandRoots(A, B, C, x);
    for (int i = 0; i < n; ++i)
      if (inS(x[i])) ext.add(tau + mu * x[i]);
  }
  // Where g = 0 runs parallel to s: b t + c s + e = 0, solved for its larger term.
  if (std::abs(g.c) >= std::abs(g.b) && g.c != 0.0) {
    const double nu = -g.b / g.c;  // s = s0 + nu t
    const double s0 = -g.e / g.c;
    const double A = g.a + (2.0 * g.b + g.c * nu) * nu;
    const double B = g.b * s0 + g.c * s0 * nu + g.d + g.e * nu;
    const double C = (g.c * s0 + 2.0 * g.e) * s0 + g.f;
    const int n = bandRoots(A, B, C, x);
    for (int i = 0; i < n; ++i) {
      const double s = s0 + nu * x[i];
      if (inS(s) && inZ(x[i], s)) ext.add(x[i]);
    }
  } else if (g.b != 0.0) {
    const double lam = -g.c / g.b;  // t = t0 + lam s
    const double t0 = -g.e / g.b;
    const double A = (g.a * lam + 2.0 * g.b) * lam + g.c;
    const double B = g.a * t0 * lam + g.b * t0 + g.d * lam + g.e;
    const double C = (g.a * t0 + 2.0 * g.d) * t0 + g.f;
    const int n = bandRoots(A, B, C, x);
    for (int i = 0; i < n; ++i) {
      const double t = t0 + lam * x[i];
      if (inS(x[i]) && inZ(t, x[i])) ext.add(t);
    }
  }
  // A singular point of g on its zero set (the apex of a cone cut through its tip).
  const double det = g.a * g.c - g.b * g.b;
  if (!(det > 0.0 && g.a > 0.0) &&
      std::abs(det) > 1e-12 * (g.a * g.a + 2.0 * g.b * g.b + g.c * g.c)) {
    const double t = (-g.d * g.c + g.e * g.b) / det;
    const double s = (-g.e * g.a + g.d * g.b) / det;
    if (g(t, s) <= tol.quadric && inS(s) && inZ(t, s)) ext.add(t);
  }
  if (!(ext.lo <= ext.hi)) return false;
  lo = ext.lo;
  hi = ext.hi;
  return true;
}

bool stripExtent(const Quadric2& g, double s0, double s1, const SectionTolerance& tol, double& lo,
                 double& hi) {
  const HalfPlane h[4] = {{0.0, -1.0, s0}, {0.0, 1.0, -s1}, {}, {}};
  const bool live[4] = {true, true, false, false};
  Extent ext;
  // No corners: the extremes are on the two edges or where g = 0 runs parallel to s.
  for (const double s : {s0, s1}) {
    const double b = g.b * s + g.d;
    const double c = (g.c * s + 2.0 * g.e) * s + g.f;
    double disc = b * b - g.a * c;
    if (disc < 0.0) {
      if (disc < -1e-12 * (b * b + std::abs(g.a * c))) continue;
      disc = 0.0;
    }
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    ext.add(q / g.a);
    if (q != 0.0) ext.add(c / q);
  }
  addLineCandidates(g, g.b, g.c, g.e, h, live, tol.linear, ext);
  if (!(ext.lo <= ext.hi)) return false;
  lo = ext.lo;
  hi = ext.hi;
  return true;
}

}  // namespace mdhd::geom

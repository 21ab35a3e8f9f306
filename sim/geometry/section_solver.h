#pragma once
// The closed-form core of every swept volume: the extent in t of a convex set in the
// (t, s) plane bounded by one quadric g(t, s) <= 0 and four half-planes.
//
// A line point at parameter t lies in the sweep of a convex piece along a segment iff
// some s in [0, L] puts (line(t) - s * dir) in the piece, and that set of (t, s) is
// convex; its projection onto t is the interval. The extremes of t lie at a vertex of
// the half-planes, where a half-plane's edge meets g = 0, where g = 0 runs parallel to
// s (dg/ds = 0), or at a singular point of g (a cone's apex): a handful of candidates.
namespace mdhd::geom {

// g(t, s) = A t^2 + 2 B t s + C s^2 + 2 D t + 2 E s + F
struct Quadric2 {
  double a = 0, b = 0, c = 0, d = 0, e = 0, f = 0;
  double operator()(double t, double s) const {
    return a * t * t + 2.0 * b * t * s + c * s * s + 2.0 * d * t + 2.0 * e * s + f;
  }
};

// n_t t + n_s s + k <= 0
struct HalfPlane {
  double nt = 0, ns = 0, k = 0;
  double operator()(double t, double s) const { return nt * t + ns * s + k; }
};

// Tolerances for candidates that sit on an edge: `linear` in the units of t and s
// (mm), `quadric` in the units of g (mm^2).
struct SectionTolerance {
  double linear = 1e-9;
  double quadric = 1e-11;
};

// The extent [lo, hi] of t over {g <= 0} and the four half-planes, which must bound a
// compact convex set. False if it is empty.
bool sectionExtent(const Quadric2& g, const HalfPlane (&h)[4], const SectionTolerance& tol,
                   double& lo, double& hi);

// The same for the shape every piece of a translational sweep gives (a band): the
// half-planes 0 <= s <= length and z0 <= zeta0 + ze t - zd s <= z1 (ze != 0), a
// parallelogram. Its four corners need no half-plane tests and each edge is one
// quadratic in one unknown: the candidates of sectionExtent at a fraction of the cost.
// open0/open1: the solid goes on smoothly past z0/z1 (smoothJoin), so that edge and
// its corners offer no candidate.
struct Band {
  double length = 0, ze = 1, zd = 0, zeta0 = 0, z0 = 0, z1 = 0;
  bool open0 = false, open1 = false;
};
bool bandExtent(const Quadric2& g, const Band& band, const SectionTolerance& tol, double& lo,
                double& hi);

// The same for the strip s0 <= s <= s1 alone, with g.a > 0 (g bounded in t): the case
// of a line perpendicular to the tool's axis, where the piece's z range only limits s.
bool stripExtent(const Quadric2& g, double s0, double s1, const SectionTolerance& tol, double& lo,
                 double& hi);

}  // namespace mdhd::geom

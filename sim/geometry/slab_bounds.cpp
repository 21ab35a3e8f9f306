#include "sim/geometry/slab_bounds.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace mdhd::geom {
namespace {

// A convex polygon of at most 4 + 6 vertices (a parallelogram clipped by six planes).
struct Polygon {
  glm::dvec3 p[10];
  int n = 0;
};

// Keeps the part of `in` where sign * (x[k] - bound) <= 0 (Sutherland-Hodgman).
void clip(const Polygon& in, int k, double bound, double sign, Polygon& out) {
  out.n = 0;
  for (int i = 0; i < in.n; ++i) {
    const glm::dvec3& a = in.p[i];
    const glm::dvec3& b = in.p[(i + 1) % in.n];
    const double da = sign * (a[k] - bound), db = sign * (b[k] - bound);
    if (da <= 0.0) out.p[out.n++] = a;
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      glm::dvec3 c = a + (da / (da - db)) * (b - a);
      c[k] = bound;  // on the plane exactly, whatever the rounding of the blend
      out.p[out.n++] = c;
    }
  }
}

}  // namespace

Aabb sweptPieceBoundsIn(const glm::dvec3& tip, const glm::dvec3& move, const glm::dvec3& axis,
                        double z0, double z1, double radius, const Aabb& box) {
  glm::dvec3 ext;
  for (int k = 0; k < 3; ++k) ext[k] = radius * std::sqrt(std::max(0.0, 1.0 - axis[k] * axis[k]));
  Polygon a, b;
  const glm::dvec3 c0 = tip + z0 * axis, c1 = tip + z1 * axis;
  a.p[0] = c0;
  a.p[1] = c0 + move;
  a.p[2] = c1 + move;
  a.p[3] = c1;
  a.n = 4;
  for (int k = 0; k < 3 && a.n > 0; ++k) {
    clip(a, k, box.hi[k] + ext[k], 1.0, b);
    clip(b, k, box.lo[k] - ext[k], -1.0, a);
  }
  Aabb r{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  if (a.n == 0) return r;
  for (int i = 0; i < a.n; ++i) {
    r.lo = glm::min(r.lo, a.p[i]);
    r.hi = glm::max(r.hi, a.p[i]);
  }
  // Grown back by the disks, a hair more for the clip's rounding; never beyond `box`.
  const double eps = 1e-9 * (1.0 + radius + std::abs(z1 - z0) + glm::length(move));
  r.lo = glm::max(r.lo - ext - eps, box.lo);
  r.hi = glm::min(r.hi + ext + eps, box.hi);
  return r;
}

}  // namespace mdhd::geom

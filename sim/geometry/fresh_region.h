#pragma once
// Where a translated tool part reaches beyond its start pose: a superset of the
// points of its sweep S that the part standing at the start pose, T(a), does not
// hold. When T(a) has been cut already (the previous step ended there), nothing
// outside this region can change, so a cut may skip it: on a raster the region is
// the leading half of the tool, about half of its box.
//
// Why it holds (T one convex body of revolution, any union of them body by body):
// a point x of S \ T(a) is x = y + s m (m the move, s in [0, 1]) for a point y
// where the segment from x - t m in T(a) leaves T(a), and the outward normal n
// there has n . m >= 0 (at a crease, one of the two pieces' normals does). On a
// piece whose side widens towards the shank and a move that does not go towards
// the tip (or the reverse), such a y lies on the front half of the side, whose
// points have (y - axis) . m_perp >= 0, and so has x; on a ball zone,
// (y - centre) . m >= 0; elsewhere (caps facing the move, pieces sloping the
// other way) only the box of the piece swept over the move bounds it.
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "sim/geometry/line_solid.h"

namespace mdhd::geom {

struct FreshPiece {
  Aabb box;
  // When set, only the points of `box` with dot(normal, x) >= offset.
  bool halfSpace = false;
  glm::dvec3 normal{0.0};
  double offset = 0.0;
};

// A union of pieces. Header-only: the stock (which does not link the geometry
// library) clips its bricks with it.
struct FreshRegion {
  std::vector<FreshPiece> pieces;
  // A box holding every point of the region inside `box`; empty (lo > hi on
  // some axis) when the region misses it.
  Aabb clip(const Aabb& box) const;
};

inline Aabb FreshRegion::clip(const Aabb& box) const {
  Aabb out{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  for (const FreshPiece& p : pieces) {
    Aabb b{glm::max(box.lo, p.box.lo), glm::min(box.hi, p.box.hi)};
    if (b.lo.x > b.hi.x || b.lo.y > b.hi.y || b.lo.z > b.hi.z) continue;
    if (p.halfSpace) {
      // n . x >= offset inside b: each coordinate is bounded by what the others
      // can contribute at most (one pass: a box holding the clipped part).
      double most = 0.0;
      glm::dvec3 best;
      for (int k = 0; k < 3; ++k) {
        best[k] = std::max(p.normal[k] * b.lo[k], p.normal[k] * b.hi[k]);
        most += best[k];
      }
      if (most < p.offset) continue;
      const Aabb whole = b;
      for (int k = 0; k < 3; ++k) {
        if (p.normal[k] == 0.0) continue;
        const double bound = (p.offset - (most - best[k])) / p.normal[k];
        if (p.normal[k] > 0.0)
          b.lo[k] = std::max(whole.lo[k], bound);
        else
          b.hi[k] = std::min(whole.hi[k], bound);
      }
    }
    out.lo = glm::min(out.lo, b.lo);
    out.hi = glm::max(out.hi, b.hi);
  }
  return out;
}

}  // namespace mdhd::geom

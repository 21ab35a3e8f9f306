#include "sim/geometry/tool_fresh_region.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace mdhd::geom {

namespace {

Aabb emptyBox() {
  return {glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
}

void include(Aabb& box, const Aabb& other) {
  box.lo = glm::min(box.lo, other.lo);
  box.hi = glm::max(box.hi, other.hi);
}

// The box of the disk of `radius` centred at `centre` square to unit `axis`.
Aabb diskBox(const glm::dvec3& centre, const glm::dvec3& axis, double radius) {
  glm::dvec3 e;
  for (int k = 0; k < 3; ++k) e[k] = radius * std::sqrt(std::max(0.0, 1.0 - axis[k] * axis[k]));
  return {centre - e, centre + e};
}

// The box of a stretch [z0, z1] of the axis at radius `radius`, swept over `move`.
Aabb sweptBox(const ToolPose& a, double z0, double z1, double radius, const glm::dvec3& move) {
  Aabb box = diskBox(a.tip + z0 * a.axis, a.axis, radius);
  include(box, diskBox(a.tip + z1 * a.axis, a.axis, radius));
  include(box, {box.lo + move, box.hi + move});
  return box;
}

}  // namespace

std::optional<FreshRegion> freshRegion(const ToolPart& part, const ToolPose& a, const ToolPose& b) {
  if (part.empty() || a.axis != b.axis) return std::nullopt;
  const glm::dvec3 w = a.axis;
  const glm::dvec3 m = b.tip - a.tip;
  const double along = glm::dot(m, w);
  const glm::dvec3 across = m - along * w;
  FreshRegion region;
  if (m == glm::dvec3(0.0)) return region;  // S is T(a): nothing new
  // Every side that faces the move only on its front half shares one half-space.
  FreshPiece front{emptyBox(), true, across, glm::dot(across, a.tip)};
  for (const ConvexBody& body : part.bodies) {
    for (const RevolvedPiece& p : body.pieces) {
      const Aabb box = sweptBox(a, p.z0, p.z1, p.maxRadius(), m);
      if (p.sphere) {
        const glm::dvec3 centre = a.tip + p.centre * w;
        region.pieces.push_back({box, true, m, glm::dot(m, centre)});
        continue;
      }
      // A side widening towards the shank (r1 > r0) has normals tilted towards
      // the tip: it faces the move only on its front half unless the move goes
      // towards the tip; one narrowing, unless the move goes towards the shank.
      const bool frontHalf = p.r1 == p.r0 || (p.r1 > p.r0 ? along >= 0.0 : along <= 0.0);
      if (frontHalf)
        include(front.box, box);
      else
        region.pieces.push_back({box, false, {}, 0.0});
    }
    // Flat ends face the move when it goes their way.
    const double rBottom = body.pieces.front().radiusAt(body.bottom());
    const double rTop = body.pieces.back().radiusAt(body.top());
    if (along < 0.0 && rBottom > 0.0)
      region.pieces.push_back(
          {sweptBox(a, body.bottom(), body.bottom(), rBottom, m), false, {}, 0.0});
    if (along > 0.0 && rTop > 0.0)
      region.pieces.push_back({sweptBox(a, body.top(), body.top(), rTop, m), false, {}, 0.0});
  }
  if (front.box.lo.x <= front.box.hi.x) region.pieces.push_back(front);
  return region;
}

}  // namespace mdhd::geom

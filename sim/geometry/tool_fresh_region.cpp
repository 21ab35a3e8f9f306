#include "sim/geometry/tool_fresh_region.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "sim/geometry/pose_interpolation.h"

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

namespace {

// Where the part's boundary can lead a turn (addTurnRegion): a stretch [z0, z1] of the
// axis (heights above the tip) out to `radius`, on the side sign * u >= 0.
struct TurnStretch {
  double z0, z1, radius;
  double sign;
};

// The stretches of one body: each side piece split where z + r r' (z above the pivot)
// changes sign, and the end faces.
void turnStretches(const ConvexBody& body, double pivotHeight, std::vector<TurnStretch>& out) {
  for (const RevolvedPiece& p : body.pieces) {
    if (!(p.z1 > p.z0)) continue;
    double g0 = 0.0, g1 = 0.0;
    if (p.sphere) {
      g0 = g1 = p.centre - pivotHeight;  // r r' = centre - z on a ball zone
    } else {
      const double slope = (p.r1 - p.r0) / (p.z1 - p.z0);
      g0 = p.z0 - pivotHeight + p.r0 * slope;
      g1 = p.z1 - pivotHeight + p.r1 * slope;
    }
    const double r = p.maxRadius();
    if (g0 >= 0.0 && g1 >= 0.0) {
      out.push_back({p.z0, p.z1, r, 1.0});
    } else if (g0 <= 0.0 && g1 <= 0.0) {
      out.push_back({p.z0, p.z1, r, -1.0});
    } else {  // linear in z: one change of sign
      const double zs = p.z0 + (p.z1 - p.z0) * g0 / (g0 - g1);
      out.push_back({p.z0, zs, r, g0 > 0.0 ? 1.0 : -1.0});
      out.push_back({zs, p.z1, r, g1 > 0.0 ? 1.0 : -1.0});
    }
  }
  const double rBottom = body.pieces.front().radiusAt(body.bottom());
  const double rTop = body.pieces.back().radiusAt(body.top());
  if (rBottom > 0.0) out.push_back({body.bottom(), body.bottom(), rBottom, 1.0});
  if (rTop > 0.0) out.push_back({body.top(), body.top(), rTop, -1.0});
}

}  // namespace

void addTurnRegion(const ToolPart& part, double pivotHeight, const glm::dvec3& pivot,
                   const glm::dvec3& from, const glm::dvec3& to, FreshRegion& region) {
  const double angle = axisAngle(from, to);
  if (angle == 0.0 || part.empty()) return;
  const glm::dvec3 k = glm::normalize(glm::cross(from, to));
  const glm::dvec3 mid = from + to;
  const glm::dvec3 u = angle > 2.0 ? glm::dvec3(0.0) : glm::cross(k, glm::normalize(mid));
  std::vector<TurnStretch> stretches;
  for (const ConvexBody& body : part.bodies) turnStretches(body, pivotHeight, stretches);
  for (const TurnStretch& st : stretches) {
    // Farthest point of the stretch from the pivot (distance^2 is convex or linear in z
    // on every piece, so at an end).
    const double rho = std::hypot(
        st.radius, std::max(std::abs(st.z0 - pivotHeight), std::abs(st.z1 - pivotHeight)));
    const ToolPose a{pivot - pivotHeight * from, from}, b{pivot - pivotHeight * to, to};
    Aabb box = sweptBox(a, st.z0, st.z1, st.radius, glm::dvec3(0.0));
    include(box, sweptBox(b, st.z0, st.z1, st.radius, glm::dvec3(0.0)));
    // A point's arc leaves the chord between its two ends by at most the sagitta.
    const double sagitta = rho * (1.0 - std::cos(0.5 * angle));
    box.lo -= glm::dvec3(sagitta);
    box.hi += glm::dvec3(sagitta);
    // Over the turn u moves by at most 2 sin(angle / 4) from its middle.
    const double slack = 2.0 * rho * std::sin(0.25 * angle);
    // Near a half turn the middle axis is ill-defined: the whole box, no half-space.
    if (angle > 2.0) {
      region.pieces.push_back({box, false, {}, 0.0});
      continue;
    }
    const glm::dvec3 n = st.sign * u;
    region.pieces.push_back({box, true, n, glm::dot(n, pivot) - slack});
  }
}

std::optional<FreshRegion> freshRegion(const ToolPart& part, const ToolPose& held,
                                       std::span<const Translation> moves) {
  if (part.empty()) return std::nullopt;
  constexpr double kSamePivot = 1e-9;  // mm
  const double h = part.turnPivot();
  FreshRegion region;
  ToolPose last = held;
  for (const Translation& t : moves) {
    if (last.axis != t.axis || last.tip != t.from) {
      const glm::dvec3 c0 = last.tip + h * last.axis, c1 = t.from + h * t.axis;
      if (!(glm::length(c1 - c0) <= kSamePivot)) return std::nullopt;
      addTurnRegion(part, h, c1, last.axis, t.axis, region);
    }
    const auto r = freshRegion(part, ToolPose{t.from, t.axis}, ToolPose{t.to, t.axis});
    if (!r) return std::nullopt;
    region.pieces.insert(region.pieces.end(), r->pieces.begin(), r->pieces.end());
    last = ToolPose{t.to, t.axis};
  }
  return region;
}

}  // namespace mdhd::geom

#include "sim/geometry/signed_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "sim/geometry/pose_interpolation.h"

namespace mdhd::geom {

namespace {

// Distances in the meridian half-plane, coordinates (rho, z).
double segmentDistance(double pr, double pz, double ar, double az, double br, double bz) {
  const double dr = br - ar;
  const double dz = bz - az;
  const double len2 = dr * dr + dz * dz;
  double f = len2 > 0.0 ? ((pr - ar) * dr + (pz - az) * dz) / len2 : 0.0;
  f = std::clamp(f, 0.0, 1.0);
  return std::hypot(pr - (ar + f * dr), pz - (az + f * dz));
}

double arcDistance(double pr, double pz, const RevolvedPiece& p) {
  const double radius = std::sqrt(p.alpha + p.centre * p.centre);
  const double a0 = std::atan2(p.z0 - p.centre, p.r0);
  const double a1 = std::atan2(p.z1 - p.centre, p.r1);
  const double ap = std::atan2(pz - p.centre, pr);
  if (ap >= a0 && ap <= a1) return std::abs(std::hypot(pr, pz - p.centre) - radius);
  return std::min(std::hypot(pr - p.r0, pz - p.z0), std::hypot(pr - p.r1, pz - p.z1));
}

}  // namespace

double signedDistance(const ConvexBody& body, const glm::dvec3& p) {
  const double pr = std::hypot(p.x, p.y);
  const double pz = p.z;
  const RevolvedPiece& first = body.pieces.front();
  const RevolvedPiece& last = body.pieces.back();
  double d = std::min(segmentDistance(pr, pz, 0.0, first.z0, first.r0, first.z0),
                      segmentDistance(pr, pz, 0.0, last.z1, last.r1, last.z1));
  for (const RevolvedPiece& piece : body.pieces) {
    d = std::min(d, piece.sphere ? arcDistance(pr, pz, piece)
                                 : segmentDistance(pr, pz, piece.r0, piece.z0, piece.r1, piece.z1));
  }
  const bool inside = pz >= body.bottom() && pz <= body.top() && pr <= body.radiusAt(pz);
  return inside ? -d : d;
}

double signedDistance(const ToolPart& part, const ToolPose& pose, const glm::dvec3& p) {
  const ToolPose q = normalizedPose(pose);
  // Tool frame: z along the axis; the radial direction is all that matters.
  const glm::dvec3 rel = p - q.tip;
  const double z = glm::dot(rel, q.axis);
  const double rho = glm::length(rel - z * q.axis);
  double d = std::numeric_limits<double>::infinity();
  for (const ConvexBody& body : part.bodies) d = std::min(d, signedDistance(body, {rho, 0.0, z}));
  return d;
}

}  // namespace mdhd::geom

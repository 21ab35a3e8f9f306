#include "sim/geometry/polyline_simplify.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace mdhd::geom {

namespace {

double squaredDistanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 d = b - a, q = p - a;
  const double dd = glm::dot(d, d);
  const double t = dd > 0.0 ? std::clamp(glm::dot(q, d) / dd, 0.0, 1.0) : 0.0;
  const glm::dvec3 e = q - t * d;
  return glm::dot(e, e);
}

}  // namespace

void simplifyPolyline(std::span<const glm::dvec3> points, std::span<const std::uint8_t> fixed,
                      double tolerance, std::vector<std::size_t>& kept) {
  kept.clear();
  const std::size_t n = points.size();
  if (n == 0) return;
  const double tol2 = tolerance * tolerance;
  // Whether every point strictly between i and j lies within the tolerance of (i, j).
  const auto fits = [&](std::size_t i, std::size_t j) {
    for (std::size_t k = i + 1; k < j; ++k)
      if (squaredDistanceToSegment(points[k], points[i], points[j]) > tol2) return false;
    return true;
  };
  kept.push_back(0);
  for (std::size_t i = 0; i + 1 < n;) {
    // The chord from i reaches as far as it can: up to a fixed point at most, and
    // no further than the first point it would leave out of the tolerance.
    std::size_t j = i + 1;
    while (j + 1 < n && !(!fixed.empty() && fixed[j] != 0) && fits(i, j + 1)) ++j;
    kept.push_back(j);
    i = j;
  }
}

}  // namespace mdhd::geom

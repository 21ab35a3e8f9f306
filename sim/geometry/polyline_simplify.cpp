#include "sim/geometry/polyline_simplify.h"

#include <algorithm>
#include <utility>

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
  if (n <= 2) {
    for (std::size_t i = 0; i < n; ++i) kept.push_back(i);
    return;
  }
  std::vector<std::uint8_t> keep(n, 0);
  keep.front() = keep.back() = 1;
  if (!fixed.empty())
    for (std::size_t i = 0; i < n; ++i) keep[i] = keep[i] | (fixed[i] != 0);
  const double tol2 = tolerance * tolerance;
  // Between each pair of neighbouring kept points, the farthest point from their
  // segment is kept while it is farther than the tolerance.
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (std::size_t i = 0, j = 1; j < n; ++j)
    if (keep[j]) {
      spans.emplace_back(i, j);
      i = j;
    }
  while (!spans.empty()) {
    const auto [i, j] = spans.back();
    spans.pop_back();
    double worst = -1.0;
    std::size_t at = i;
    for (std::size_t k = i + 1; k < j; ++k) {
      const double d2 = squaredDistanceToSegment(points[k], points[i], points[j]);
      if (d2 > worst) worst = d2, at = k;
    }
    if (at == i || !(worst > tol2)) continue;
    keep[at] = 1;
    spans.emplace_back(i, at);
    spans.emplace_back(at, j);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) kept.push_back(i);
}

}  // namespace mdhd::geom

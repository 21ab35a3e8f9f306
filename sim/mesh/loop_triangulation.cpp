#include "sim/mesh/loop_triangulation.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace mdhd::mesh {

namespace {

// Shape quality of a triangle facing along `normal`: the square of twice its area
// over the sum of its squared sides (largest for an equilateral; squared, so no
// root: only its order matters), negative if it faces away or is degenerate.
double quality(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
               const glm::dvec3& normal) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double len2 = glm::dot(n, n);
  if (len2 <= kMinDoubleArea * kMinDoubleArea || glm::dot(n, normal) <= 0.0) return -1.0;
  const glm::dvec3 ab = b - a, bc = c - b, ca = a - c;
  const double sides = glm::dot(ab, ab) + glm::dot(bc, bc) + glm::dot(ca, ca);
  return len2 / (sides * sides);
}

}  // namespace

bool triangulateLoop(std::span<const glm::dvec3> p, std::span<const std::uint8_t> masks,
                     std::vector<std::array<int, 3>>& out, glm::dvec3& centre) {
  const int n = static_cast<int>(p.size());
  if (n == 3) {
    out.push_back({0, 1, 2});
    return true;
  }
  // Newell's normal: the direction the polygon faces.
  glm::dvec3 normal(0.0);
  for (int i = 0; i < n; ++i) normal += glm::cross(p[i], p[(i + 1) % n]);
  // The fan from k is (k, k+1, k+2), (k, k+2, k+3), ..., (k, k-2, k-1): its first and
  // last triangles are ears (three consecutive corners), each shared by two fans, so
  // each ear's quality is computed once (a quad's four triangles are all ears).
  constexpr int kMaxCorners = 16;
  double ear[kMaxCorners];
  const bool cached = n <= kMaxCorners;
  if (cached)
    for (int i = 0; i < n; ++i) ear[i] = quality(p[i], p[(i + 1) % n], p[(i + 2) % n], normal);
  int bestApex = -1;
  double bestScore = 0.0;
  for (int k = 0; k < n; ++k) {
    double score = 1e300;
    for (int i = 1; i + 1 < n && score > 0.0; ++i) {
      const int j = (k + i) % n, j1 = (k + i + 1) % n;
      if (i >= 2 && (masks[k] & masks[j]) != 0)
        score = -1.0;
      else if (cached && i == 1)
        score = std::min(score, ear[k]);
      else if (cached && i == n - 2)
        score = std::min(score, ear[j]);
      else
        score = std::min(score, quality(p[k], p[j], p[j1], normal));
    }
    if (score > bestScore) {
      bestScore = score;
      bestApex = k;
    }
  }
  if (bestApex >= 0) {
    for (int i = 1; i + 1 < n; ++i)
      out.push_back({bestApex, (bestApex + i) % n, (bestApex + i + 1) % n});
    return true;
  }
  centre = glm::dvec3(0.0);
  for (const glm::dvec3& q : p) centre += q;
  centre /= double(n);
  for (int i = 0; i < n; ++i) out.push_back({n, i, (i + 1) % n});
  return false;
}

}  // namespace mdhd::mesh

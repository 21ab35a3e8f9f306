#include "sim/mesh/loop_triangulation.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace mdhd::mesh {

namespace {

// Shape quality of a triangle facing along `normal`: the square of twice its area
// over the sum of its squared sides (largest for an equilateral; squared, so no
// root: only its order matters), negative if it faces away or is degenerate.
// Written out in glm::cross's and glm::dot's order of operations (the same bits):
// the hottest function of meshing, a third faster without the vector temporaries.
double quality(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
               const glm::dvec3& normal) {
  const double abx = b.x - a.x, aby = b.y - a.y, abz = b.z - a.z;
  const double acx = c.x - a.x, acy = c.y - a.y, acz = c.z - a.z;
  const double nx = aby * acz - acy * abz;
  const double ny = abz * acx - acz * abx;
  const double nz = abx * acy - acx * aby;
  const double len2 = nx * nx + ny * ny + nz * nz;
  if (len2 <= kMinDoubleArea * kMinDoubleArea ||
      nx * normal.x + ny * normal.y + nz * normal.z <= 0.0)
    return -1.0;
  const double bcx = c.x - b.x, bcy = c.y - b.y, bcz = c.z - b.z;
  const double cax = a.x - c.x, cay = a.y - c.y, caz = a.z - c.z;
  const double sides = (abx * abx + aby * aby + abz * abz) + (bcx * bcx + bcy * bcy + bcz * bcz) +
                       (cax * cax + cay * cay + caz * caz);
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
  if (n == 4) {
    // A quad (most loops): the general search below, unrolled. Fans 0 and 2 share
    // the diagonal 0-2 and their two ears, as 1 and 3 share 1-3; a later fan wins
    // only when strictly better.
    double e[4];
    for (int i = 0; i < 4; ++i) e[i] = quality(p[i], p[(i + 1) % 4], p[(i + 2) % 4], normal);
    const auto fan = [&](int k) {
      const double first = std::min(1e300, e[k]);
      if (!(first > 0.0)) return first;
      return (masks[k] & masks[k + 2]) != 0 ? -1.0 : std::min(first, e[k + 2]);
    };
    const double s0 = fan(0), s1 = fan(1);
    const int apex = s1 > std::max(s0, 0.0) ? 1 : s0 > 0.0 ? 0 : -1;
    if (apex >= 0) {
      out.push_back({apex, apex + 1, apex + 2});
      out.push_back({apex, apex + 2, (apex + 3) % 4});
      return true;
    }
  }
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

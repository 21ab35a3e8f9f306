// triangulateLoop picks, among the fans whose diagonals avoid the cube's faces,
// the one whose worst triangle is best shaped; a centre vertex only when no fan
// qualifies. Checked against a brute force over all fans on random polygons.
#include "sim/mesh/loop_triangulation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace mdhd::mesh {
namespace {

// Twice the area over the sum of squared sides; -1 if facing away or degenerate.
double shape(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& n) {
  const glm::dvec3 x = glm::cross(b - a, c - a);
  if (glm::length(x) <= kMinDoubleArea || glm::dot(x, n) <= 0.0) return -1.0;
  return glm::length(x) /
         (glm::dot(b - a, b - a) + glm::dot(c - b, c - b) + glm::dot(a - c, a - c));
}

struct Fan {
  int apex = -1;
  double score = -1.0;  // the worst triangle's shape, -1 if a diagonal is not allowed
};

Fan bestFan(const std::vector<glm::dvec3>& p, const std::vector<std::uint8_t>& masks) {
  const int n = static_cast<int>(p.size());
  glm::dvec3 normal(0.0);
  for (int i = 0; i < n; ++i) normal += glm::cross(p[i], p[(i + 1) % n]);
  Fan best;
  for (int k = 0; k < n; ++k) {
    double worst = 1e300;
    for (int i = 1; i + 1 < n; ++i) {
      const int j = (k + i) % n;
      if (i >= 2 && (masks[k] & masks[j]) != 0) worst = -1.0;
      worst = std::min(worst, shape(p[k], p[j], p[(j + 1) % n], normal));
    }
    if (worst > best.score) best = {k, worst};
  }
  return best;
}

// A polygon of n corners around a wobbly circle in a tilted plane, some dents.
std::vector<glm::dvec3> polygon(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> r(0.3, 1.0), z(-0.2, 0.2), jitter(-0.3, 0.3);
  std::vector<glm::dvec3> p;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * std::numbers::pi * (i + jitter(rng)) / n;
    p.push_back({r(rng) * std::cos(phi), r(rng) * std::sin(phi), z(rng)});
  }
  return p;
}

TEST(LoopTriangulation, TakesTheBestShapedFanOrAddsACentre) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> corners(4, 9), face(0, 5);
  int fans = 0, centres = 0, blocked = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int n = corners(rng);
    const std::vector<glm::dvec3> p = polygon(rng, n);
    std::vector<std::uint8_t> masks(n);
    for (auto& m : masks) m = static_cast<std::uint8_t>((1u << face(rng)) | (1u << face(rng)));
    std::vector<std::array<int, 3>> out;
    glm::dvec3 centre(0.0);
    const bool plain = triangulateLoop(p, masks, out, centre);
    const Fan ref = bestFan(p, masks);
    if (!plain) {
      ++centres;
      EXPECT_LE(ref.score, 1e-12) << trial;  // no fan qualified
      ASSERT_EQ(static_cast<int>(out.size()), n);
      continue;
    }
    ++fans;
    ASSERT_EQ(static_cast<int>(out.size()), n - 2) << trial;
    const int k = out[0][0];
    for (int i = 0; i + 2 < n; ++i) {
      EXPECT_EQ(out[i][0], k);
      EXPECT_EQ(out[i][1], (k + i + 1) % n);
      EXPECT_EQ(out[i][2], (k + i + 2) % n);
    }
    // Its worst triangle is as good as the best fan's (up to rounding: ears are
    // measured once for both fans that hold them).
    double worst = 1e300;
    glm::dvec3 normal(0.0);
    for (int i = 0; i < n; ++i) normal += glm::cross(p[i], p[(i + 1) % n]);
    for (const auto& t : out) {
      if (t[1] != (k + 1) % n) blocked += (masks[t[0]] & masks[t[1]]) != 0;
      worst = std::min(worst, shape(p[t[0]], p[t[1]], p[t[2]], normal));
    }
    EXPECT_GT(worst, 0.0) << trial;
    EXPECT_GE(worst, ref.score * (1 - 1e-12)) << trial;
  }
  EXPECT_EQ(blocked, 0);  // no diagonal joins two points of one cube face
  EXPECT_GT(fans, 1000);
  EXPECT_GT(centres, 10);
}

TEST(LoopTriangulation, ATriangleIsItself) {
  const std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint8_t> masks = {1, 2, 4};
  std::vector<std::array<int, 3>> out;
  glm::dvec3 centre(0.0);
  EXPECT_TRUE(triangulateLoop(p, masks, out, centre));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], (std::array<int, 3>{0, 1, 2}));
}

}  // namespace
}  // namespace mdhd::mesh

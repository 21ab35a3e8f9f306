// Chords that reach as far as they can on tool tips: every dropped point within the tolerance of
// the segment that replaces it, the ends and fixed points kept, straight runs dropped.
#include "sim/geometry/polyline_simplify.h"

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace mdhd::geom {
namespace {

double distanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 d = b - a;
  const double t =
      glm::dot(d, d) > 0 ? std::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * d));
}

TEST(PolylineSimplify, DroppedPointsStayWithinTheTolerance) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<std::size_t> kept;
  int dropped = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // A raster-like chain: short steps along a slowly bending direction, with noise
    // and now and then a sharp turn; some points fixed.
    const int n = 2 + static_cast<int>(rng() % 40);
    const double tol = 0.001 * (1 + rng() % 20);
    std::vector<glm::dvec3> pts;
    std::vector<std::uint8_t> fixed;
    glm::dvec3 p(0.0), dir(1.0, 0.0, 0.0);
    for (int i = 0; i < n; ++i) {
      pts.push_back(p);
      fixed.push_back(rng() % 7 == 0);
      if (rng() % 10 == 0) dir = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)));
      dir = glm::normalize(dir + 0.02 * glm::dvec3(unit(rng), unit(rng), unit(rng)));
      p += 0.5 * dir + 0.002 * glm::dvec3(unit(rng), unit(rng), unit(rng));
    }
    simplifyPolyline(pts, fixed, tol, kept);
    ASSERT_FALSE(kept.empty());
    EXPECT_EQ(kept.front(), 0u);
    EXPECT_EQ(kept.back(), pts.size() - 1);
    for (std::size_t j = 0; j + 1 < kept.size(); ++j) {
      ASSERT_LT(kept[j], kept[j + 1]);
      for (std::size_t k = kept[j] + 1; k < kept[j + 1]; ++k) {
        EXPECT_FALSE(fixed[k]) << trial << " " << k;
        EXPECT_LE(distanceToSegment(pts[k], pts[kept[j]], pts[kept[j + 1]]), tol * (1 + 1e-12))
            << trial << " " << k;
        ++dropped;
      }
    }
  }
  EXPECT_GT(dropped, 1000);  // the bending runs do shorten
}

TEST(PolylineSimplify, StraightRunsGoAndZigzagsStay) {
  std::vector<glm::dvec3> line;
  for (int i = 0; i < 10; ++i) line.push_back(glm::dvec3(0.5 * i, 0.25 * i, -0.1 * i));
  std::vector<std::size_t> kept;
  simplifyPolyline(line, {}, 1e-12, kept);  // collinear but for rounding
  EXPECT_EQ(kept, (std::vector<std::size_t>{0, 9}));
  // A zigzag of amplitude 2 tol keeps every point; of amplitude tol / 2, only its ends.
  for (const double amplitude : {0.02, 0.005}) {
    std::vector<glm::dvec3> zig;
    for (int i = 0; i < 9; ++i) zig.push_back(glm::dvec3(0.5 * i, 0.0, i % 2 ? amplitude : 0.0));
    simplifyPolyline(zig, {}, 0.01, kept);
    EXPECT_EQ(kept.size(), amplitude > 0.01 ? 9u : 2u) << amplitude;
  }
  // A fixed point stays, even on a straight run.
  std::vector<std::uint8_t> fixed(10, 0);
  fixed[4] = 1;
  simplifyPolyline(line, fixed, 0.01, kept);
  EXPECT_EQ(kept, (std::vector<std::size_t>{0, 4, 9}));
  simplifyPolyline(std::vector<glm::dvec3>{}, {}, 0.01, kept);
  EXPECT_TRUE(kept.empty());
}

// A raster pass over a dome (radius 83 mm, steps of 0.5 mm, half the default tolerance):
// a chord of three steps stays within 0.005 mm (sagitta 0.0034), of four it does not
// (0.0060). Every chord but the last spans three steps, whatever the chain's length:
// halving (Douglas-Peucker) fell to chords of two on chains of 16 or 32 steps.
TEST(PolylineSimplify, ChordsOnAnArcReachAsFarAsTheToleranceLets) {
  const double radius = 83.0, step = 0.5, tol = 0.005;
  std::vector<std::size_t> kept;
  for (const int steps : {16, 24, 32, 48}) {
    std::vector<glm::dvec3> arc;
    for (int i = 0; i <= steps; ++i) {
      const double a = i * step / radius;
      arc.push_back(glm::dvec3(radius * std::sin(a), 0.0, radius * std::cos(a)));
    }
    simplifyPolyline(arc, {}, tol, kept);
    ASSERT_EQ(kept.size(), static_cast<std::size_t>((steps + 2) / 3 + 1)) << steps;
    for (std::size_t j = 0; j + 2 < kept.size(); ++j) EXPECT_EQ(kept[j + 1] - kept[j], 3u) << steps;
  }
}

}  // namespace
}  // namespace mdhd::geom

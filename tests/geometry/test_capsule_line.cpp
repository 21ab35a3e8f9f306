// A line through a capsule (a ball swept along a segment) in closed form, against the
// distance from the line's points to the segment: the ends are where that distance
// is the radius, and lines that pass farther miss.
#include "sim/geometry/capsule_line.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

double distanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& d,
                         double len) {
  const double s = std::clamp(glm::dot(p - a, d), 0.0, len);
  return glm::length(p - (a + s * d));
}

TEST(CapsuleLine, EndsAreWhereTheDistanceIsTheRadius) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const glm::dvec3 origin(3 * uni(rng), 3 * uni(rng), 3 * uni(rng));
    glm::dvec3 e = testing::randomUnit(rng);
    glm::dvec3 d = testing::randomUnit(rng);
    if (trial % 5 == 0) d = e;   // along the line
    if (trial % 7 == 0) d = -e;  // against it
    const double len = trial % 11 == 0 ? 0.0 : 4.0 * std::abs(uni(rng));
    const double r = 0.3 + 2.0 * std::abs(uni(rng));
    const glm::dvec3 a(uni(rng), uni(rng), uni(rng));  // the segment's start
    const glm::dvec3 m = origin - a;
    double lo = 0.0, hi = 0.0;
    const bool hit = capsuleExtent(glm::dot(m, e), glm::dot(m, d), glm::dot(m, m), glm::dot(e, d),
                                   len, r, lo, hi);
    // The distance along the line is convex: its least, by golden sections.
    double t0 = -20.0, t1 = 20.0;
    const auto dist = [&](double t) { return distanceToSegment(origin + t * e, a, d, len); };
    for (int i = 0; i < 200; ++i) {
      const double x1 = t0 + 0.382 * (t1 - t0), x2 = t0 + 0.618 * (t1 - t0);
      (dist(x1) < dist(x2) ? t1 : t0) = dist(x1) < dist(x2) ? x2 : x1;
    }
    const double least = dist(0.5 * (t0 + t1));
    if (least > r - 1e-9) {
      EXPECT_FALSE(hit && hi - lo > 1e-6) << trial;
      ++misses;
      continue;
    }
    ASSERT_TRUE(hit) << trial;
    ++hits;
    EXPECT_NEAR(dist(lo), r, 1e-9) << trial;
    EXPECT_NEAR(dist(hi), r, 1e-9) << trial;
    EXPECT_LT(dist(0.5 * (lo + hi)), r) << trial;
  }
  EXPECT_GT(hits, 800);
  EXPECT_GT(misses, 300);
}

}  // namespace
}  // namespace mdhd::geom

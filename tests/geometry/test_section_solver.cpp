// The closed-form section extent against a brute-force scan over s, on random convex
// problems (ellipses, strips and cone sections cut by four half-planes).
#include "sim/geometry/section_solver.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace mdhd::geom {
namespace {

// The feasible t range at one s, exactly: the quadric's roots cut by the half-planes.
bool tRangeAt(const Quadric2& g, const HalfPlane (&h)[4], double s, double& lo, double& hi) {
  lo = -1e9;
  hi = 1e9;
  for (const HalfPlane& p : h) {
    const double rest = p.ns * s + p.k;
    if (p.nt > 0) hi = std::min(hi, -rest / p.nt);
    if (p.nt < 0) lo = std::max(lo, -rest / p.nt);
    if (p.nt == 0 && rest > 0) return false;
  }
  const double a = g.a;
  const double b = g.b * s + g.d;
  const double c = g.c * s * s + 2 * g.e * s + g.f;
  if (a > 0) {
    const double disc = b * b - a * c;
    if (disc < 0) return false;
    lo = std::max(lo, (-b - std::sqrt(disc)) / a);
    hi = std::min(hi, (-b + std::sqrt(disc)) / a);
  } else if (b != 0) {
    (b > 0 ? hi : lo) = b > 0 ? std::min(hi, -c / (2 * b)) : std::max(lo, -c / (2 * b));
  } else if (c > 0) {
    return false;
  }
  return lo <= hi;
}

// A convex quadric: |M (t, s) + m|^2 - r^2 with M of rank 1 or 2.
Quadric2 randomQuadric(std::mt19937& rng, bool rankOne) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double m00 = u(rng), m01 = u(rng), m10 = u(rng), m11 = u(rng);
  if (rankOne) m10 = 0, m11 = 0;
  const double c0 = u(rng), c1 = u(rng);
  const double r = 0.2 + std::abs(u(rng));
  Quadric2 g;
  g.a = m00 * m00 + m10 * m10;
  g.b = m00 * m01 + m10 * m11;
  g.c = m01 * m01 + m11 * m11;
  g.d = m00 * c0 + m10 * c1;
  g.e = m01 * c0 + m11 * c1;
  g.f = c0 * c0 + c1 * c1 - r * r;
  return g;
}

TEST(SectionSolver, RandomProblemsMatchABruteForceScan) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int nonEmpty = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Quadric2 g = randomQuadric(rng, trial % 4 == 0);
    const double len = trial % 7 == 0 ? 0.0 : 2.0 * std::abs(u(rng));
    // s in [0, len] and a random slab n . (t, s) in [k0, k1], like the tool's z range.
    const double nt = u(rng), ns = u(rng);
    const double k0 = u(rng), k1 = k0 + 0.1 + std::abs(u(rng));
    const HalfPlane h[4] = {{0, -1, 0}, {0, 1, -len}, {-nt, -ns, k0}, {nt, ns, -k1}};
    double lo = 0, hi = 0;
    const bool found = sectionExtent(g, h, SectionTolerance{1e-12, 1e-13}, lo, hi);
    double blo = 1e300, bhi = -1e300;
    const int n = 4000;
    for (int i = 0; i <= n; ++i) {
      const double s = len * i / n;
      double a, b;
      if (!tRangeAt(g, h, s, a, b)) continue;
      blo = std::min(blo, a);
      bhi = std::max(bhi, b);
    }
    const bool bruteFound = blo <= bhi;
    if (bruteFound) {
      ASSERT_TRUE(found) << "trial " << trial;
      ++nonEmpty;
      // The solver's extent holds every sampled point and is no wider than sampling
      // between the samples allows.
      EXPECT_LE(lo, blo + 1e-9) << "trial " << trial;
      EXPECT_GE(hi, bhi - 1e-9) << "trial " << trial;
      EXPECT_GE(lo, blo - 2e-3) << "trial " << trial;
      EXPECT_LE(hi, bhi + 2e-3) << "trial " << trial;
    } else if (found) {
      // Only a sliver thinner than the sampling may be missed by the scan.
      EXPECT_LT(hi - lo, 0.05) << "trial " << trial;
    }
  }
  EXPECT_GT(nonEmpty, 500);
}

TEST(SectionSolver, ConeThroughItsApex) {
  // g = t^2 - s^2 (a cone's section through its apex) with s >= 0 (the nappe):
  // the wedge |t| <= s, for s in [0, 2]: t in [-2, 2]; cut at s >= 1 by the slab.
  const Quadric2 g{1, 0, -1, 0, 0, 0};
  const HalfPlane h[4] = {{0, -1, 0}, {0, 1, -2}, {0, -1, 1}, {0, 1, -5}};
  double lo = 0, hi = 0;
  ASSERT_TRUE(sectionExtent(g, h, SectionTolerance{}, lo, hi));
  EXPECT_DOUBLE_EQ(lo, -2.0);
  EXPECT_DOUBLE_EQ(hi, 2.0);
  // Only the apex itself: s in [0, 0].
  const HalfPlane apex[4] = {{0, -1, 0}, {0, 1, 0}, {-1, 0, -5}, {1, 0, -5}};
  ASSERT_TRUE(sectionExtent(g, apex, SectionTolerance{}, lo, hi));
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_DOUBLE_EQ(hi, 0.0);
}

TEST(SectionSolver, EmptyAndAllOrNothingHalfPlanes) {
  const Quadric2 disk{1, 0, 1, 0, 0, -1};  // t^2 + s^2 <= 1
  double lo = 0, hi = 0;
  const HalfPlane far[4] = {{0, -1, 2}, {0, 1, -3}, {0, 0, -1}, {0, 0, -1}};  // s in [2, 3]
  EXPECT_FALSE(sectionExtent(disk, far, SectionTolerance{}, lo, hi));
  const HalfPlane never[4] = {{0, -1, 0}, {0, 1, -1}, {0, 0, 1}, {0, 0, -1}};  // 1 <= 0
  EXPECT_FALSE(sectionExtent(disk, never, SectionTolerance{}, lo, hi));
  const HalfPlane always[4] = {{0, -1, 0}, {0, 1, -0.6}, {0, 0, -1}, {0, 0, -1}};
  ASSERT_TRUE(sectionExtent(disk, always, SectionTolerance{}, lo, hi));
  EXPECT_DOUBLE_EQ(lo, -1.0);  // the disk's widest point, s = 0
  EXPECT_DOUBLE_EQ(hi, 1.0);
}

}  // namespace
}  // namespace mdhd::geom

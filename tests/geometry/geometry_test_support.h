#pragma once
// Shared by the geometry tests: tools, line-integrated volumes and a brute-force
// membership reference built on signed distances (code independent of the sweep's).
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/line_solid.h"
#include "sim/geometry/signed_distance.h"
#include "sim/geometry/tool.h"
#include "sim/geometry/tool_part.h"

namespace mdhd::geom::testing {

inline constexpr double kPi = std::numbers::pi;

inline Tool makeTool(ToolShape shape, double diameter = 6.0, double flutes = 12.0) {
  Tool t;
  t.number = 1;
  t.shape = shape;
  t.diameter = diameter;
  t.flute_length = flutes;
  t.length = 50.0;
  t.shank_diameter = diameter;
  if (shape == ToolShape::kBull) t.corner_radius = 1.0;
  if (shape == ToolShape::kDrill) t.tip_angle = 118.0;
  t.holder = {{20.0, 15.0}, {30.0, 10.0}};
  return t;
}

// A random unit vector, none of whose draws was too short to normalise well.
inline glm::dvec3 randomUnit(std::mt19937& rng) {
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  glm::dvec3 v;
  do v = {uni(rng), uni(rng), uni(rng)};
  while (glm::dot(v, v) < 0.04);
  return glm::normalize(v);
}

inline std::vector<ToolShape> allShapes() {
  return {ToolShape::kFlat, ToolShape::kBall, ToolShape::kBull, ToolShape::kDrill};
}

// Volume as the sum of interval lengths over lines through the centres of an h grid.
inline double integrateVolume(const LineSolid& solid, int axis, double h) {
  const Aabb b = solid.bounds();
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  std::vector<Interval> out;
  double sum = 0.0;
  for (double u = std::floor(b.lo[i1] / h) * h + h / 2; u < b.hi[i1]; u += h)
    for (double v = std::floor(b.lo[i2] / h) * h + h / 2; v < b.hi[i2]; v += h) {
      out.clear();
      solid.lineIntervals(axis, u, v, out);
      for (const Interval& iv : out) sum += iv.hi - iv.lo;
    }
  return sum * h * h;
}

// Volume of a part from its pieces (frustums exactly, sphere zones exactly).
inline double partVolume(const ToolPart& part) {
  double v = 0.0;
  for (const ConvexBody& b : part.bodies)
    for (const RevolvedPiece& p : b.pieces) {
      // integral of pi (alpha + beta z + gamma z^2) dz
      auto prim = [&](double z) {
        return kPi * (p.alpha * z + p.beta * z * z / 2 + p.gamma * z * z * z / 3);
      };
      v += prim(p.z1) - prim(p.z0);
    }
  return v;
}

// Area of the meridian section (both sides of the axis) of one convex body.
inline double sectionArea(const ConvexBody& b) {
  double a = 0.0;
  const int n = 20000;
  const double dz = (b.top() - b.bottom()) / n;
  for (int i = 0; i < n; ++i) a += 2.0 * b.radiusAt(b.bottom() + (i + 0.5) * dz) * dz;
  return a;
}

using Sdf = std::function<double(const glm::dvec3&)>;

// Checks a line of `solid` against a signed distance: every interval end lies on the
// surface (|sd| < endTol) and every sample farther than `band` from the surface is
// inside an interval exactly when sd < 0. Returns the number of decided samples.
inline int checkLine(const LineSolid& solid, const Sdf& sd, int axis, double u, double v,
                     double band, double endTol, double step) {
  std::vector<Interval> out;
  solid.lineIntervals(axis, u, v, out);
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  auto point = [&](double t) {
    glm::dvec3 p;
    p[axis] = t;
    p[i1] = u;
    p[i2] = v;
    return p;
  };
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_LT(out[i].lo, out[i].hi);
    if (i > 0) {
      EXPECT_LT(out[i - 1].hi, out[i].lo) << "intervals must be sorted and disjoint";
    }
    if (endTol > 0) {
      EXPECT_NEAR(sd(point(out[i].lo)), 0.0, endTol) << "axis " << axis << " u " << u << " v " << v;
      EXPECT_NEAR(sd(point(out[i].hi)), 0.0, endTol) << "axis " << axis << " u " << u << " v " << v;
    }
  }
  const Aabb b = solid.bounds();
  int decided = 0;
  for (double t = b.lo[axis] - 0.5; t <= b.hi[axis] + 0.5; t += step) {
    const double d = sd(point(t));
    if (std::abs(d) <= band) continue;
    bool in = false;
    for (const Interval& iv : out) in = in || (t >= iv.lo && t <= iv.hi);
    EXPECT_EQ(in, d < 0) << "axis " << axis << " u " << u << " v " << v << " t " << t << " sd "
                         << d;
    ++decided;
  }
  return decided;
}

// Minimum over s in [0, 1] of a function convex in s (golden-section search).
inline double minimiseConvex(const std::function<double(double)>& f) {
  double a = 0.0;
  double b = 1.0;
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - r * (b - a);
  double d = a + r * (b - a);
  double fc = f(c);
  double fd = f(d);
  for (int i = 0; i < 60; ++i) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - r * (b - a);
      fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + r * (b - a);
      fd = f(d);
    }
  }
  return std::min({f(0.0), f(1.0), fc, fd});
}

}  // namespace mdhd::geom::testing

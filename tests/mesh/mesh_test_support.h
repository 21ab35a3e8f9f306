#pragma once
// Shared by the mesh tests: small exact solids, real tools, meshing into an
// indexed mesh and the checks every mesh must pass.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/line_solid.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool.h"
#include "sim/geometry/tool_part.h"
#include "sim/mdh/stock.h"
#include "sim/mesh/indexed_mesh.h"
#include "sim/mesh/mesher.h"
#include "tests/mdh/random_tool_moves.h"

namespace mdhd::mesh::testing {

inline constexpr double kPi = std::numbers::pi;

// A ball of radius r: exact line intervals.
class Ball final : public geom::LineSolid {
 public:
  Ball(glm::dvec3 c, double r) : c_(c), r_(r) {}
  geom::Aabb bounds() const override { return {c_ - glm::dvec3(r_), c_ + glm::dvec3(r_)}; }
  void lineIntervals(int axis, double u, double v,
                     std::vector<geom::Interval>& out) const override {
    const double du = u - c_[(axis + 1) % 3], dv = v - c_[(axis + 2) % 3];
    const double s = r_ * r_ - du * du - dv * dv;
    if (s <= 0) return;
    out.push_back({c_[axis] - std::sqrt(s), c_[axis] + std::sqrt(s)});
  }

 private:
  glm::dvec3 c_;
  double r_;
};

// An axis-aligned box.
class Block final : public geom::LineSolid {
 public:
  Block(glm::dvec3 lo, glm::dvec3 hi) : lo_(lo), hi_(hi) {}
  geom::Aabb bounds() const override { return {lo_, hi_}; }
  void lineIntervals(int axis, double u, double v,
                     std::vector<geom::Interval>& out) const override {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    if (u < lo_[a] || u > hi_[a] || v < lo_[b] || v > hi_[b]) return;
    out.push_back({lo_[axis], hi_[axis]});
  }

 private:
  glm::dvec3 lo_, hi_;
};

// A cutter of the given shape and diameter (flutes 4 d, shank as thick).
inline geom::ToolPart toolPart(geom::ToolShape shape, double diameter) {
  return mdh::testing::cutterPart(shape, diameter);
}

inline glm::dvec3 tilted(double degrees, const glm::dvec3& towards) {
  const double a = degrees * kPi / 180.0;
  return glm::normalize(std::cos(a) * glm::dvec3(0, 0, 1) + std::sin(a) * glm::normalize(towards));
}

inline mdh::StockOptions stockOptions(double density, bool threeWay = true, int brick = 32) {
  mdh::StockOptions o;
  o.density = density;
  o.three_way = threeWay;
  o.brick = brick;
  o.threads = 1;
  return o;
}

struct Meshed {
  IndexedMesh mesh;
  MeshStats stats;
};

inline Meshed meshOf(const mdh::Stock& stock, const MeshOptions& options = {}) {
  Meshed m;
  m.stats = meshStock(stock, m.mesh, options);
  return m;
}

// Closed, oriented, manifold, no degenerate triangle, no engine disagreement.
inline void expectWatertight(const Meshed& m) {
  const EdgeReport e = checkEdges(m.mesh);
  EXPECT_EQ(e.open, 0);
  EXPECT_EQ(e.overused, 0);
  EXPECT_EQ(e.sameDirection, 0);
  EXPECT_EQ(e.collapsed, 0);
  EXPECT_EQ(nonManifoldVertices(m.mesh), 0);
  EXPECT_EQ(m.stats.degenerateTriangles, 0);
  EXPECT_EQ(m.stats.fallbackCrossings, 0);  // the engine's leaves agree (shared_samples.h)
  EXPECT_GT(smallestTriangleArea(m.mesh), 0.0);
  EXPECT_EQ(m.stats.triangles, static_cast<std::int64_t>(m.mesh.triangles().size()));
}

}  // namespace mdhd::mesh::testing

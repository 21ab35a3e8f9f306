#pragma once
// Random 5-axis moves of real tools (ball, flat, bull, drill from
// sim/geometry) from every side of a stock box, tilted up to about 35
// degrees: the sweeps the shared-sample tests cut. Every draw is sequenced, so
// a seed gives the same moves with any compiler.
#include <random>

#include <glm/geometric.hpp>

#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool.h"
#include "sim/geometry/tool_part.h"

namespace mdhd::mdh::testing {

inline geom::ToolPart cutterPart(geom::ToolShape shape, double diameter) {
  geom::Tool t;
  t.number = 1;
  t.shape = shape;
  t.diameter = diameter;
  t.flute_length = 4 * diameter;
  t.length = 10 * diameter;
  t.shank_diameter = diameter;
  if (shape == geom::ToolShape::kBull) t.corner_radius = diameter / 4;
  if (shape == geom::ToolShape::kDrill) t.tip_angle = 118.0;
  return geom::makeToolPart(t, geom::ToolPartKind::kCutter);
}

struct ToolMove {
  geom::SweptVolume sweep;
  glm::dvec3 direction;  // tip to spindle, the mean of the two poses
};

class RandomToolMoves {
 public:
  // Moves whose tips lie in [lo + 1, hi - 1] (x, y) and the upper part of the box (z).
  RandomToolMoves(std::uint32_t seed, const geom::Aabb& box) : rng_(seed), box_(box) {}

  ToolMove next() {
    const geom::ToolShape shapes[] = {geom::ToolShape::kBall, geom::ToolShape::kFlat,
                                      geom::ToolShape::kBull, geom::ToolShape::kDrill};
    const geom::ToolShape shape = shapes[rng_() % 4];
    const double diameter = 0.8 + 1.2 * unit();
    const geom::ToolPart part = cutterPart(shape, diameter);
    glm::dvec3 base(0, 0, 1);
    const int side = rng_() % 6;
    if (side == 4) base = {1, 0, 0};
    if (side == 5) base = {0, -1, 0.2};
    const glm::dvec3 a0 = axis(base), a1 = axis(base);
    const glm::dvec3 t0 = tip(a0), t1 = tip(a1);
    return {geom::SweptVolume::between(part, {t0, a0}, {t1, a1}, 0, 0.01), glm::normalize(a0 + a1)};
  }

 private:
  double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
  glm::dvec3 axis(const glm::dvec3& base) {
    const double x = unit() - 0.5, y = unit() - 0.5, z = unit() - 0.5;
    const double tilt = 0.7 * unit();
    return glm::normalize(glm::normalize(base) + tilt * glm::normalize(glm::dvec3(x, y, z)));
  }
  glm::dvec3 tip(const glm::dvec3& axis) {
    const double x = unit(), y = unit(), z = unit();
    const glm::dvec3 span = box_.hi - box_.lo;
    const glm::dvec3 p(box_.lo.x + 1 + (span.x - 2) * x, box_.lo.y + 1 + (span.y - 2) * y,
                       box_.lo.z + span.z * (0.375 + 0.625 * z));
    return p - axis * 0.5;  // reach a little into the stock along the axis
  }

  std::mt19937 rng_;
  geom::Aabb box_;
};

}  // namespace mdhd::mdh::testing

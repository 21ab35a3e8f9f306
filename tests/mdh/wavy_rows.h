#pragma once
// Chains of tool poses the fresh-region and batched-cut tests cut, on a 12 x 12 x 8
// stock at density 10 cut on one thread.
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/geometry/tool_pose.h"
#include "sim/mdh/stock.h"

namespace mdhd::mdh::testing {

inline const geom::Aabb kWavyStock{{0, 0, 0}, {12, 12, 8}};

// One instance, copied by each stock (made in place per test, gcc 12 warned of
// an uninitialised read inside the ruleset's initializer list).
inline const StockOptions& wavyOptions() {
  static const StockOptions o = [] {
    StockOptions x;
    x.density = 10.0;
    x.threads = 1;
    return x;
  }();
  return o;
}

// A zigzag of five rows over a wavy floor, `steps` steps of `spacing` mm a row:
// every step goes sideways and up or down a little (no two on one line), the axis
// held (tilted when `axis` is).
inline std::vector<geom::ToolPose> wavyRows(const glm::dvec3& axis, int steps, double spacing) {
  std::vector<geom::ToolPose> poses;
  for (int row = 0; row < 5; ++row)
    for (int i = 0; i <= steps; ++i) {
      const double x = 1.0 + (row % 2 == 0 ? i : steps - i) * spacing;
      const double y = 2.0 + row * 1.7;
      const double z = 5.0 + 0.8 * std::sin(0.7 * x) * std::cos(0.5 * y);
      poses.push_back({{x, y, z}, axis});
    }
  return poses;
}

// The same zigzag with the axis turning a little every step (about +-7 degrees over a
// row): a 5-axis chain.
inline std::vector<geom::ToolPose> turningRows(int steps, double spacing) {
  auto poses = wavyRows({0, 0, 1}, steps, spacing);
  for (geom::ToolPose& p : poses)
    p.axis = glm::normalize(
        glm::dvec3(0.12 * std::sin(0.5 * p.tip.x), 0.1 * std::cos(0.4 * p.tip.x + p.tip.y), 1.0));
  return poses;
}

}  // namespace mdhd::mdh::testing

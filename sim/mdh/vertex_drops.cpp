#include "sim/mdh/vertex_drops.h"

#include <algorithm>
#include <cmath>

namespace mdhd::mdh {

VertexDrops::VertexDrops(const GridSpec& grid, const std::vector<std::array<int, 3>>& vertices)
    : grid_(grid) {
  bool first = true;
  for (const auto& p : vertices) {
    for (int a = 0; a < 3; ++a) {
      const double lo = grid.toMm(a, p[a] - kDropHalfWidth);
      const double hi = grid.toMm(a, p[a] + kDropHalfWidth);
      bounds_.lo[a] = first ? lo : std::min(bounds_.lo[a], lo);
      bounds_.hi[a] = first ? hi : std::max(bounds_.hi[a], hi);
      lines_[{a, p[axisU(a)], p[axisV(a)]}].push_back(p[a]);
    }
    first = false;
  }
  if (first) bounds_ = {glm::dvec3(1.0), glm::dvec3(0.0)};  // no vertex: an empty box
  for (auto& [line, levels] : lines_) {
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  }
}

void VertexDrops::lineIntervals(int axis, double u, double v,
                                std::vector<geom::Interval>& out) const {
  const int iu = static_cast<int>(std::lround(grid_.toGrid(axisU(axis), u)));
  const int iv = static_cast<int>(std::lround(grid_.toGrid(axisV(axis), v)));
  const auto it = lines_.find({axis, iu, iv});
  if (it == lines_.end()) return;
  for (int k : it->second)
    out.push_back({grid_.toMm(axis, k - kDropHalfWidth), grid_.toMm(axis, k + kDropHalfWidth)});
}

}  // namespace mdhd::mdh

#pragma once
// Vertices one cell had to drop (a forced one-cube cell, see cut_cell.cpp),
// as a solid the other cells holding them cut like any tool: an open
// interval of kDropHalfWidth grid units around each vertex along each of the
// three grid lines through it. Every holder then removes the vertex by the
// same rules as a real cut (vertex_rule.h) and puts the crossings of its
// edges kDropHalfWidth from it, so all of them store the same samples and
// the solid keeps all but a sliver of its volume.
#include <array>
#include <map>
#include <tuple>
#include <vector>

#include "sim/geometry/line_solid.h"
#include "sim/mdh/grid.h"

namespace mdhd::mdh {

// Wider than IntervalCache's grazing chords (kMinToolSpan), which it drops.
inline constexpr double kDropHalfWidth = 1e-3;

class VertexDrops final : public geom::LineSolid {
 public:
  VertexDrops(const GridSpec& grid, const std::vector<std::array<int, 3>>& vertices);
  geom::Aabb bounds() const override { return bounds_; }
  void lineIntervals(int axis, double u, double v, std::vector<geom::Interval>& out) const override;

 private:
  const GridSpec& grid_;
  geom::Aabb bounds_;
  std::map<std::tuple<int, int, int>, std::vector<int>> lines_;  // (axis, iu, iv) -> levels
};

}  // namespace mdhd::mdh

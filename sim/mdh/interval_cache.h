#pragma once
// The tool's intervals for one in-between step, along every grid line its
// bounds reach, in grid units. Each row of lines is computed once, on first
// use, by whichever thread gets there first, and then shared by every cell.
// A row keeps only the extent where its lines hit the tool (thesis 5.2.2's
// fix for the 45-degree waste).
#include <array>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "sim/geometry/line_solid.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/line_segments.h"

namespace mdhd::mdh {

class IntervalCache {
 public:
  IntervalCache(const GridSpec& grid, const geom::LineSolid& solid);
  ~IntervalCache();
  IntervalCache(const IntervalCache&) = delete;
  IntervalCache& operator=(const IntervalCache&) = delete;

  // Vertex box covering the solid's bounds, clipped to the stock (may be empty).
  const GridBox& touched() const { return touched_; }
  // Open intervals of the tool along the line of `axis` through vertex indices
  // (iu, iv) on axes (axis+1)%3 and (axis+2)%3; empty outside the bounds.
  std::span<const Span> line(int axis, int iu, int iv) const;
  // How many lineIntervals calls were made (for tests of "once per line").
  std::size_t queries() const;

 private:
  struct Row;
  void fill(int axis, Row& row, int iv) const;

  const GridSpec& grid_;
  const geom::LineSolid& solid_;
  GridBox touched_;
  std::array<std::vector<std::unique_ptr<Row>>, 3> rows_;
};

}  // namespace mdhd::mdh

#pragma once
// Good-bad maps (thesis 3.1): for one axis, a pixel per grid line along it
// through the cell, saying whether the surface on that line could be held by
// a heightmap along the axis (good: at most one crossing, signed by which side
// is solid) or not (bad), and whether the line meets the unresolved surface.
#include <cstdint>
#include <vector>

#include "sim/mdh/direction.h"
#include "sim/mdh/sample_grid.h"

namespace mdhd::mdh {

enum class Pixel : std::uint8_t { kUnsigned, kPositive, kNegative, kBad };

struct GoodBadMap {
  int axis = 0;
  int p = 1, q = 2;    // pixel axes: axisU(axis), axisV(axis)
  int p0 = 0, q0 = 0;  // absolute vertex index of pixel (0, 0)
  int np = 0, nq = 0;
  std::vector<Pixel> type;
  std::vector<std::uint8_t> unresolved;
  bool hasBad = false, hasPositive = false, hasNegative = false, hasUnresolvedBad = false;

  std::size_t at(int ip, int iq) const { return static_cast<std::size_t>(iq) * np + ip; }
  bool valid() const { return !hasBad && !(hasPositive && hasNegative); }
  Direction validDirection() const { return Direction{axis, hasNegative ? -1 : 1}; }
};

// Marks the vertices next to the part of the new surface the old direction
// cannot hold (thesis 3.2: the unresolved surface), on every column that has
// become invalid for `old`: between the first and last crossing it cannot
// hold, those with a crossing on one of their edges. A pixel is unresolved
// when one of its ray's own crossings has a marked end.
void markUnresolved(SampleGrid& g, Direction old);

GoodBadMap buildGoodBadMap(const SampleGrid& g, int axis);

}  // namespace mdhd::mdh

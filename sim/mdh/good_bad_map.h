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
  int positives = 0, negatives = 0;

  std::size_t at(int ip, int iq) const { return static_cast<std::size_t>(iq) * np + ip; }
  // A two-sided map (three_map.h) holds conflicting signs: only bad pixels count.
  bool valid(bool twoSided = false) const {
    return !hasBad && (twoSided || !(hasPositive && hasNegative));
  }
  // The side most lines take (a two-sided map flips the others).
  Direction validDirection() const { return Direction{axis, negatives > positives ? -1 : 1}; }
};

// Marks the vertices next to the part of the new surface the old direction
// cannot hold (thesis 3.2: the unresolved surface), on every column that has
// become invalid for `old`: between the first and last crossing it cannot
// hold, those with a crossing on one of their edges. A pixel is unresolved
// when one of its ray's own crossings has a marked end. `oldMap` (its box that
// of g, direction `old`): a two-sided map's columns, each on its own side.
// `twoSided`: a column either side holds is resolved (the map flips it).
void markUnresolved(SampleGrid& g, Direction old, const ThreeMap* oldMap = nullptr,
                    bool twoSided = false);

GoodBadMap buildGoodBadMap(const SampleGrid& g, int axis);

}  // namespace mdhd::mdh

#pragma once
// A cell (or part of one) unpacked into vertex states and edge crossings: the
// common ground on which a cut is applied, good-bad maps are read, and a
// heightmap in any of the six directions is packed again. Because every
// stored height is an edge crossing at an absolute coordinate, unpacking and
// packing in another direction moves no sample: this is the resampling of
// thesis 7.4 without a second simulation pass.
#include <cstdint>
#include <vector>

#include "sim/mdh/direction.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

class SampleGrid {
 public:
  static constexpr std::uint8_t kSolid = 1;       // solid after this step's cut
  static constexpr std::uint8_t kWasSolid = 2;    // solid before it
  static constexpr std::uint8_t kUnresolved = 4;  // next to the unresolved surface

  explicit SampleGrid(const GridBox& box);
  static SampleGrid solid(const GridBox& box);
  static SampleGrid decode(const ThreeMap& map, const GridBox& sub);

  const GridBox& box() const { return box_; }
  int size(int axis) const { return n_[axis]; }
  std::size_t index(int x, int y, int z) const {  // absolute vertex indices
    return static_cast<std::size_t>(x - box_.lo[0]) +
           static_cast<std::size_t>(n_[0]) *
               (static_cast<std::size_t>(y - box_.lo[1]) +
                static_cast<std::size_t>(n_[1]) * static_cast<std::size_t>(z - box_.lo[2]));
  }
  std::size_t index(const std::array<int, 3>& p) const { return index(p[0], p[1], p[2]); }
  std::size_t stride(int axis) const {
    return axis == 0 ? 1 : axis == 1 ? n_[0] : static_cast<std::size_t>(n_[0]) * n_[1];
  }
  std::uint8_t& state(std::size_t i) { return state_[i]; }
  std::uint8_t state(std::size_t i) const { return state_[i]; }
  bool solidAt(std::size_t i) const { return state_[i] & kSolid; }
  // Crossing on the edge from vertex i to i + stride(axis) (NaN if none).
  double& crossing(int axis, std::size_t i) { return cross_[axis][i]; }
  double crossing(int axis, std::size_t i) const { return cross_[axis][i]; }

  // Subtracts the step's tool: vertex states by vertex_rule.h, then every
  // edge of all three families gets its crossing from edgeCrossingAfterCut.
  // `reach` (when given; the whole box otherwise): the vertices the cut can change
  // and the edges between them (CutContext::reach): lines outside it keep theirs
  // without asking the solid.
  void applyCut(const IntervalCache& cache, const GridBox* reach = nullptr);
  bool changed() const { return changed_; }

  // Whether every line along d.axis is solid-then-empty for d (a heightmap can hold it).
  bool columnValid(Direction d, int u, int v) const;
  // Height of the column along d.axis through (u, v) on axes axisU/axisV of d.
  double columnHeight(Direction d, int u, int v) const;
  // The same for a two-sided map in direction d: the column on d's side if d holds
  // it, else flipped if the opposite side does; false if neither does.
  bool twoSidedColumn(Direction d, int u, int v, double& height, bool& flipped) const;

 private:
  GridBox box_;
  std::array<int, 3> n_;
  std::vector<std::uint8_t> state_;
  std::array<std::vector<double>, 3> cross_;
  bool changed_ = false;
};

// Appends the crossings g holds on a map's grid edge at the levels `st` lists: the
// edge along axis x from coordinate `edge`, in the row at coordinate `row` on axis y
// (x, y: the map's u and v axes in either order); h0, h1 are the edge's two column
// heights, for the interpolated crossing where g has none.
void appendEdgeCrossings(const SampleGrid& g, const ThreeMap& map, const ColumnStraddle& st, int x,
                         int edge, int y, int row, double h0, double h1, std::vector<double>& out);

// Packs a whole cell (g covers the cell's box) into a heightmap in direction d;
// every line along d.axis must be valid for d, or, `twoSided`, for d or its
// opposite (those valid only for the opposite become flipped columns).
ThreeMap encodeMap(const SampleGrid& g, Direction d, bool threeWay, bool twoSided = false);

}  // namespace mdhd::mdh

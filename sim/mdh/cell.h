#pragma once
// A node of the kD-tree. Leaves are solid, empty (no grid at all) or partial
// (a heightmap); inner nodes hold a grid-aligned split plane and two children
// that share the plane's vertices.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>

#include "sim/geometry/line_solid.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

enum class CellState : std::uint8_t { kEmpty, kSolid, kPartial, kInner };

inline constexpr double kStaleVolume = std::numeric_limits<double>::quiet_NaN();

// Cuts whose crossings across a z map's columns are not all computed yet (lazy
// crossings, lazy_crossings.h): the last few a cell took, oldest first, each with
// the solid that made it, the part of the cell it reached and its generation (the
// cell's count of lazy cuts). Their columns are cut; their x and y grid lines are
// asked only for the crossings still there when someone needs them.
struct PendingCut {
  std::shared_ptr<const geom::LineSolid> solid;
  GridBox reach;
  std::uint32_t generation = 0;
};
struct PendingCuts {
  // A crossing a cut made is kept uncomputed through this many cuts of its cell at
  // most: the next pass of a raster takes most of a groove's wall away.
  static constexpr int kMax = 4;
  std::array<PendingCut, kMax> cuts;
  int count = 0;
  std::uint32_t generation = 0;  // the newest cut's (0: none yet)
};

struct Cell {
  GridBox box;
  CellState state = CellState::kSolid;
  std::uint64_t id = 0;  // stable identity: the Random-Selection rule's key
  double volume = 0.0;   // grid units^3; kStaleVolume when not kept (StockOptions::step_volumes)
  int splitAxis = -1;
  int splitAt = 0;
  std::unique_ptr<ThreeMap> map;
  std::unique_ptr<PendingCuts> pending;  // partial leaves with a z map only
  std::unique_ptr<Cell> child[2];

  double boxVolume() const {
    return double(box.cubes(0)) * double(box.cubes(1)) * double(box.cubes(2));
  }
};

// A deep copy of `from`'s subtree into `to` (stock_clone.cpp).
void copyCell(const Cell& from, Cell& to);

}  // namespace mdhd::mdh

#pragma once
// A node of the kD-tree. Leaves are solid, empty (no grid at all) or partial
// (a heightmap); inner nodes hold a grid-aligned split plane and two children
// that share the plane's vertices.
#include <cstdint>
#include <limits>
#include <memory>

#include "sim/geometry/line_solid.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

enum class CellState : std::uint8_t { kEmpty, kSolid, kPartial, kInner };

inline constexpr double kStaleVolume = std::numeric_limits<double>::quiet_NaN();

// A cut whose crossings across a z map's columns are not computed yet (lazy
// crossings, lazy_crossings.h): the solid that made it and the part of the cell it
// reached. Its columns are cut; its x and y grid lines are asked only for the
// crossings that are still there when someone needs them. No solid: none pending.
struct PendingCut {
  std::shared_ptr<const geom::LineSolid> solid;
  GridBox reach;
  explicit operator bool() const { return solid != nullptr; }
};

struct Cell {
  GridBox box;
  CellState state = CellState::kSolid;
  std::uint64_t id = 0;  // stable identity: the Random-Selection rule's key
  double volume = 0.0;   // grid units^3; kStaleVolume when not kept (StockOptions::step_volumes)
  int splitAxis = -1;
  int splitAt = 0;
  std::unique_ptr<ThreeMap> map;
  PendingCut pending;  // partial leaves with a z map only
  std::unique_ptr<Cell> child[2];

  double boxVolume() const {
    return double(box.cubes(0)) * double(box.cubes(1)) * double(box.cubes(2));
  }
};

// A deep copy of `from`'s subtree into `to` (stock_clone.cpp).
void copyCell(const Cell& from, Cell& to);

}  // namespace mdhd::mdh

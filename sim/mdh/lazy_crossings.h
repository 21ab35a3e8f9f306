#pragma once
// Lazy crossings. A 3-axis batch cut into a z map (fastCutLazy) changes its columns
// at once and leaves the crossings across them (the embedded heights on the x and y
// grid lines) to be computed when needed: most crossings a raster pass makes lie on
// the wall beside its groove, which the next pass cuts away, and those never are
// (docs/engine.md, "Lazy crossings").
//
// A cell keeps its last few lazy cuts (PendingCuts, oldest first, generations g0,
// g0+1, ..., gn). An embedded height is then either
//   - a number: the crossing after every cut but the newest, which still has to be
//     applied where it reached; or
//   - a NaN tagged with the generation g of the cut that made the edge straddle that
//     level (both columns were solid there before it): cuts g .. gn have to be applied.
// Applying cut j is edgeCrossingAfterCut of the crossing so far, the columns' states
// (a straddle keeps its solid side as long as it lasts, so the states now are the
// states then), and cut j's line: the same inputs, and so the same bits, as an eager
// cut would have used. A crossing is computed when its oldest cut leaves the ring, or
// when someone reads the map (settle); a level that stops straddling before that is
// never computed at all.
#include <cstddef>
#include <cstdint>
#include <span>

#include "sim/mdh/cell.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

// The NaN an embedded height holds while the cut of `generation` is pending there.
double pendingCrossing(std::uint32_t generation);

// Before a lazy cut: brings the numbers up to the newest pending cut and, when the ring
// is full, computes the crossings its oldest cut left (and drops that cut), both only at
// levels the coming cut leaves straddled (`countsNow`, `countsAfter`: the solid vertex
// count of every column before and after it, row-major); the others are about to go.
void advanceCrossings(ThreeMap& map, PendingCuts& pending, const GridSpec& grid,
                      const int* countsNow, const int* countsAfter);

// Computes every pending crossing of `map` and empties `pending`.
void settleCrossings(ThreeMap& map, PendingCuts& pending, const GridSpec& grid);

// Lays the embedded rows out for columns whose solid counts go from `before` to
// `after` (row-major; `moved`: the indices of the columns whose height moved, the
// only ones whose count can differ): a level straddled before and after keeps its
// value, a level straddled only after gets `fresh`, one straddled only before goes.
void relayoutCrossings(ThreeMap& map, const int* before, const int* after,
                       std::span<const std::size_t> moved, double fresh);

// Settles a leaf's pending cuts, if any, and forgets them.
void settlePending(Cell& cell, const GridSpec& grid);

}  // namespace mdhd::mdh

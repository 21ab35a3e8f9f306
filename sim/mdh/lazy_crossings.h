#pragma once
// Lazy crossings. A 3-axis batch cut into a z map (fastCutLazy) changes its columns
// at once and leaves the crossings across them (the embedded heights on the x and y
// grid lines) to be computed when needed: by the cell's next cut, only for the
// crossings that cut leaves in place, or by settleCrossings before anyone reads the
// map. Most crossings a raster pass makes lie on the wall beside its groove, which the
// next pass cuts away; computed lazily, those never are (docs/engine.md, "Lazy
// crossings").
//
// While a cut is pending, an embedded height holds the crossing the edge had before
// that cut, or NaN where it had none (both columns solid at that level). The crossing
// after the cut is edgeCrossingAfterCut of that, the columns as they are now and the
// pending solid's line: the same inputs, and so the same bits, as the cut would have
// used had it computed the crossing itself.
#include <cstddef>
#include <span>

#include "sim/mdh/cell.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

// Computes the pending cut's crossings in `map` (a 3-way z map). With `countsAfter`
// (the solid vertex count of every column after the cut about to be made, row-major),
// only the levels that cut leaves straddled are computed: the others are about to go.
void settleCrossings(ThreeMap& map, const PendingCut& pending, const GridSpec& grid,
                     const int* countsAfter = nullptr);

// Lays the embedded rows out for columns whose solid counts go from `before` to
// `after` (row-major; `moved`: the indices of the columns whose height moved, the
// only ones whose count can differ): a level straddled before and after keeps its
// value, a level straddled only after gets NaN (pending), one straddled only before goes.
void relayoutCrossings(ThreeMap& map, const int* before, const int* after,
                       std::span<const std::size_t> moved);

// Settles a leaf's pending cut, if any, and forgets it.
void settlePending(Cell& cell, const GridSpec& grid);

}  // namespace mdhd::mdh

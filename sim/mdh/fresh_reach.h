#pragma once
// A fresh region (geom::FreshRegion: where a cut can still find material) as the
// grid vertices it lets a cut move.
#include "sim/geometry/fresh_region.h"
#include "sim/mdh/grid.h"

namespace mdhd::mdh {

// The vertices of `box` a change inside `fresh` can move (crossings on edges with
// an end in it included): `box` itself without a region, empty when it misses.
GridBox freshReach(const GridSpec& grid, const GridBox& box, const geom::FreshRegion* fresh);

}  // namespace mdhd::mdh

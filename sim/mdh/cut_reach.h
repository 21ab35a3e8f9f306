#pragma once
// The grid vertices a cut can move inside a box: those near where its solid lies
// there (LineSolid::boundsIn: a leaning tool's box is far wider than the part of it in
// one brick) and, when given, inside the fresh region (geom::FreshRegion: where the
// cut can still find material).
#include "sim/geometry/fresh_region.h"
#include "sim/geometry/line_solid.h"
#include "sim/mdh/grid.h"

namespace mdhd::mdh {

// The vertices of `box` a change by `solid` inside `fresh` (null: anywhere) can move,
// crossings on edges with an end in it included; empty when it misses.
GridBox cutReach(const GridSpec& grid, const GridBox& box, const geom::LineSolid& solid,
                 const geom::FreshRegion* fresh);

}  // namespace mdhd::mdh

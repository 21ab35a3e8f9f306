#pragma once
// A cut into a two-sided map (three_map.h) that its own direction still holds,
// column by column on either side: the columns under the tool are unpacked over
// the map's whole height, cut, and packed again in place, with the rows of
// embedded heights through them rebuilt. The fast path (fast_cut.h) is one-sided;
// without this a cell holding both sides is unpacked whole at every cut.
#include "sim/mdh/grid.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

enum class TwoSidedCut { kUnchanged, kDone, kInvalid };

// `reach` (inside cache.touched()): the vertices the cut can change and the edges
// between them. kInvalid: a column under the tool holds more than one crossing (the
// slow path's case); the map is untouched. On kDone *volumeDelta (unless null) is the
// volume's change in grid units^3.
TwoSidedCut twoSidedCut(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                        double* volumeDelta);

}  // namespace mdhd::mdh

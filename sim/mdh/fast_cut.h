#pragma once
// The common case of a cut: the cell's own direction still holds the result.
// Only the columns the tool reaches are recomputed (interval arithmetic on
// their one solid segment), and only the rows of embedded heights through the
// changed columns are rebuilt.
#include "sim/mdh/grid.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

enum class FastCut { kUnchanged, kDone, kOverhang };

// On kDone the map is updated and volumeDelta (grid units^3) is its change;
// on kOverhang the map is untouched.
FastCut fastCut(ThreeMap& map, const IntervalCache& cache, double& volumeDelta);

// Whether the tool removes any length from the lines along `axis` through a solid box.
bool toolReachesSolid(const GridBox& box, int axis, const IntervalCache& cache);

}  // namespace mdhd::mdh

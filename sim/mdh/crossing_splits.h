#pragma once
// Planes along a good-bad map's own axis that separate crossings on its lines:
// between two crossings of a bad line, or between a positive and a negative
// line's crossing (a sign conflict of neighbouring lines, which no plane across
// the lines can separate, as children share the plane's pixels). Not in the
// thesis: asked only when its split types offer no plane (features below a grid
// step), instead of halving the cell blindly.
#include <vector>

#include "sim/mdh/good_bad_map.h"
#include "sim/mdh/sample_grid.h"
#include "sim/mdh/split_candidate.h"

namespace mdhd::mdh {

// The runs of planes strictly inside `cell` that separate the most bad lines
// (if the map has bad pixels) or the most positive/negative line pairs (if it
// has a sign conflict); nothing if no plane separates any.
void crossingSplits(const SampleGrid& g, const GoodBadMap& map, const GridBox& cell,
                    std::vector<SplitCandidate>& out);

}  // namespace mdhd::mdh

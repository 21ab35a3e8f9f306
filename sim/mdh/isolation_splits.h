#pragma once
// Sign conflict splits (thesis 3.2.1) and indirect splits (3.2.2): both
// isolate an unresolved good region of a good-bad map from the regions that
// conflict with it, by comparing the regions' projections onto the map's two
// axes. Indirect: the conflicts are bad regions (so the region can take the
// map's direction). Sign conflict: the map has no bad pixels, and the
// conflicts are good regions of the opposite sign.
#include <vector>

#include "sim/mdh/good_bad_map.h"
#include "sim/mdh/split_candidate.h"

namespace mdhd::mdh {

void isolationSplits(const GoodBadMap& map, int oldAxis, const GridBox& cell,
                     std::vector<SplitCandidate>& out);

}  // namespace mdhd::mdh

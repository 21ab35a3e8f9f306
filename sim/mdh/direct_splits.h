#pragma once
// Direct split plane series (thesis 3.2.3): from the rays of a good-bad map's
// unresolved pixels, the tool segments and the solid segments directly left
// and right of them are grouped into overlap sets (ComputeOverlapIntervals:
// ComputeSets, ExpandSets, ComputeSets, RelaxSets); every plane inside an
// overlap interval cuts all its segments, so it divides the surface on their
// left from the surface on their right.
#include <vector>

#include "sim/mdh/good_bad_map.h"
#include "sim/mdh/sample_grid.h"
#include "sim/mdh/split_candidate.h"

namespace mdhd::mdh {

// A segment between two successive crossings on a ray, as the range of planes
// that cut it, with whether each end lies on the unresolved surface.
struct DspSegment {
  int lo = 0;
  int hi = 0;
  bool unresolvedL = false;
  bool unresolvedR = false;
  bool alive = true;
};

// The four steps of ComputeOverlapIntervals on prepared segment lists (sorted
// by ray, then along the ray); `unresolved` bounds the unresolved surface in
// plane units. Returns the overlap intervals.
std::vector<DspSegment> computeOverlapIntervals(DspSegment unresolved, std::vector<DspSegment> left,
                                                std::vector<DspSegment> tool,
                                                std::vector<DspSegment> right);

void directSplits(const SampleGrid& g, const GoodBadMap& map, const GridBox& cell,
                  std::vector<SplitCandidate>& out);

}  // namespace mdhd::mdh

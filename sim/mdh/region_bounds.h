#pragma once
// Good-bad map region bounding (thesis 5.3): tight bounding rectangles of the
// 4-connected regions of pixels that pass a test, found row by row.
#include <functional>
#include <vector>

#include "sim/mdh/good_bad_map.h"

namespace mdhd::mdh {

struct PixelRect {
  int p0 = 0, p1 = 0;  // absolute vertex indices along the map's p axis (inclusive)
  int q0 = 0, q1 = 0;
};

std::vector<PixelRect> regionBounds(const GoodBadMap& map,
                                    const std::function<bool(std::size_t)>& member);

}  // namespace mdhd::mdh

#include "sim/mdh/fresh_reach.h"

#include <algorithm>
#include <cmath>

namespace mdhd::mdh {

GridBox freshReach(const GridSpec& grid, const GridBox& box, const geom::FreshRegion* fresh) {
  if (fresh == nullptr) return box;
  geom::Aabb mm;
  for (int a = 0; a < 3; ++a) {
    mm.lo[a] = grid.toMm(a, box.lo[a]);
    mm.hi[a] = grid.toMm(a, box.hi[a]);
  }
  const geom::Aabb c = fresh->clip(mm);
  GridBox r;
  for (int a = 0; a < 3; ++a) {
    if (!(c.lo[a] <= c.hi[a])) return GridBox{{1, 1, 1}, {0, 0, 0}};
    // Outwards, and a little more for the intervals' snapping (1e-9): a point of
    // the region inside a grid edge reaches both of its ends.
    constexpr double kSlack = 1e-6;
    r.lo[a] = static_cast<int>(std::clamp(std::floor(grid.toGrid(a, c.lo[a]) - kSlack),
                                          double(box.lo[a]), double(box.hi[a])));
    r.hi[a] = static_cast<int>(std::clamp(std::ceil(grid.toGrid(a, c.hi[a]) + kSlack),
                                          double(box.lo[a]), double(box.hi[a])));
  }
  return r;
}

}  // namespace mdhd::mdh

#include "sim/mdh/cut_reach.h"

#include <algorithm>
#include <cmath>

namespace mdhd::mdh {

GridBox cutReach(const GridSpec& grid, const GridBox& box, const geom::LineSolid& solid,
                 const geom::FreshRegion* fresh) {
  if (box.empty()) return box;
  geom::Aabb mm;
  for (int a = 0; a < 3; ++a) {
    mm.lo[a] = grid.toMm(a, box.lo[a]);
    mm.hi[a] = grid.toMm(a, box.hi[a]);
  }
  if (fresh != nullptr) mm = fresh->clip(mm);
  const geom::Aabb c = solid.boundsIn(mm);
  GridBox r;
  for (int a = 0; a < 3; ++a) {
    if (!(c.lo[a] <= c.hi[a])) return GridBox{{1, 1, 1}, {0, 0, 0}};
    // Outwards, and a little more for the intervals' snapping (1e-9): a point of
    // the solid inside a grid edge reaches both of its ends.
    constexpr double kSlack = 1e-6;
    r.lo[a] = static_cast<int>(std::clamp(std::floor(grid.toGrid(a, c.lo[a]) - kSlack),
                                          double(box.lo[a]), double(box.hi[a])));
    r.hi[a] = static_cast<int>(std::clamp(std::ceil(grid.toGrid(a, c.hi[a]) + kSlack),
                                          double(box.lo[a]), double(box.hi[a])));
  }
  return r;
}

}  // namespace mdhd::mdh

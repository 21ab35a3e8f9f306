#pragma once
// CutCell (thesis figure 3.1): subtract one step's tool from a subtree. A leaf
// whose heightmap still holds the result is updated in place, touching only
// the columns and rows the tool reaches; otherwise the cell is unpacked,
// its three good-bad maps decide whether a new direction holds it (resampled
// in place), and if none does it is split by the chosen split plane and both
// children are cut again.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/geometry/fresh_region.h"
#include "sim/mdh/cell.h"
#include "sim/mdh/cut_counters.h"
#include "sim/mdh/fast_cut.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/split_rules.h"

namespace mdhd::mdh {

struct CutContext {
  const GridSpec& grid;
  const IntervalCache& cache;
  // Where the cut can change anything: the cache's box, or less (Stock::cut's fresh region).
  GridBox reach;
  // That region, when there is one: each cell's reach is clipped to it again, closer
  // than its brick's box.
  const geom::FreshRegion* fresh = nullptr;
  const std::vector<Rule>& rules;
  bool volumes = true;  // keep cells' volumes (and counters.removed) up to date
  bool threeWay = true;
  bool twoSided = false;  // StockOptions::two_sided
  glm::dvec3 toolDirection{0.0, 0.0, 1.0};
  double toolRadius = 0.0;  // grid units
  std::uint64_t seed = 1;
  std::uint64_t step = 0;
  CutCounters& counters;
  // When set (the solid being cut), 3-way z maps take the cut with their crossings
  // left pending (lazy_crossings.h); other maps settle theirs and cut as usual.
  std::shared_ptr<const geom::LineSolid> lazySolid = nullptr;
};

void cutCell(Cell& cell, const CutContext& ctx);

// A lazy batch (ctx.lazySolid) in two halves, so that a batch the fast path cannot
// take changes no cell and needs no copies to undo (Stock::cutIfFast): planLazyCut
// finds a brick's new column heights without changing it, cutPlanned makes the cut.
struct LazyPlan {
  enum class Kind {
    kNothing,  // the cut changes nothing here
    kCut,      // changes (and map, for a solid brick) hold the cut
    kRefuse,   // the brick needs the slow path: so would the batch
    kOther,    // not a leaf with a z map (or solid, one will hold it): cut it with cutCell
  };
  Kind kind = Kind::kNothing;
  std::unique_ptr<ThreeMap> map;  // a solid brick's first map
  std::vector<ColumnChange> changes;
};
LazyPlan planLazyCut(const Cell& brick, const CutContext& ctx);
void cutPlanned(Cell& brick, LazyPlan& plan, const CutContext& ctx);

// Throws std::logic_error naming the first broken invariant of the subtree.
void checkCell(const Cell& cell);

}  // namespace mdhd::mdh

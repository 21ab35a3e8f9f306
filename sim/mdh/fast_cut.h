#pragma once
// The common case of a cut: the cell's own direction still holds the result.
// Only the columns the tool reaches are recomputed (interval arithmetic on
// their one solid segment); rows of embedded heights through changed columns
// are rebuilt, and in the other rows the tool's box reaches the crossings move
// in place (a cut can move a crossing without changing any column).
#include <memory>
#include <span>
#include <vector>

#include "sim/mdh/cell.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {

enum class FastCut { kUnchanged, kDone, kOverhang };

// A column's new height (iu, iv: its place in the map).
struct ColumnChange {
  int iu, iv;
  double height;
};

// On kDone the map is updated and *volumeDelta (grid units^3, unless null:
// the edge integrals are then skipped) is its change; on kOverhang the map is
// untouched. `reach` (inside cache.touched()): the vertices the cut can
// change, and the edges between them. *columnsMoved (unless null): whether a
// column moved (kDone may move crossings only).
FastCut fastCut(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                double* volumeDelta, bool* columnsMoved = nullptr);

// The same cut into a 3-way z map with its crossings left pending (lazy_crossings.h):
// the crossings the cut leaves in place are brought up to the cuts before it as
// lazy_crossings.h's advanceCrossings says, the ones it makes are tagged with its
// generation, and `solid` joins `pending`. kDone whenever the cut reaches the map
// (whether a crossing moves is known only once it is settled); on kOverhang neither
// map nor `pending` changed.
FastCut fastCutLazy(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                    const std::shared_ptr<const geom::LineSolid>& solid, PendingCuts& pending,
                    bool* columnsMoved = nullptr);

// fastCutLazy in two halves, for a caller that must know that every cell takes the
// cut before it changes any (Stock::cutIfFast, without copies to undo): the columns'
// new heights (kUnchanged: the reach misses the map; `changes` filled on kDone), then
// the cut itself from them.
FastCut lazyColumns(const ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
                    std::vector<ColumnChange>& changes);
void cutLazily(ThreeMap& map, const IntervalCache& cache, const GridBox& reach,
               std::span<const ColumnChange> changes,
               const std::shared_ptr<const geom::LineSolid>& solid, PendingCuts& pending);

}  // namespace mdhd::mdh

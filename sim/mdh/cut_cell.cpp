#include "sim/mdh/cut_cell.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "sim/mdh/crossing_splits.h"
#include "sim/mdh/cut_reach.h"
#include "sim/mdh/direct_splits.h"
#include "sim/mdh/fast_cut.h"
#include "sim/mdh/good_bad_map.h"
#include "sim/mdh/isolation_splits.h"
#include "sim/mdh/lazy_crossings.h"
#include "sim/mdh/rng.h"
#include "sim/mdh/sample_grid.h"
#include "sim/mdh/two_sided_cut.h"
#include "sim/mdh/vertex_drops.h"
#include "sim/mdh/vertex_rule.h"

namespace mdhd::mdh {

namespace {

// The direction a solid cell takes when first cut: the stock axis closest to
// the tool's axis, solid on the side away from the spindle.
Direction guessDirection(const glm::dvec3& t) {
  int axis = 2;
  for (int a = 0; a < 2; ++a)
    if (std::abs(t[a]) > std::abs(t[axis])) axis = a;
  if (t[axis] == 0.0) return Direction{2, 1};
  return Direction{axis, t[axis] > 0 ? 1 : -1};
}

void setVolume(Cell& cell, double volume, const CutContext& ctx) {
  ctx.counters.removed += cell.volume - volume;
  cell.volume = volume;
}

// Solid and empty partial cells give their grid back.
void normalize(Cell& cell) {
  if (cell.state != CellState::kPartial) return;
  if (cell.map->allEmpty()) {
    cell.state = CellState::kEmpty;
    cell.map.reset();
    cell.pending.reset();
    cell.volume = 0.0;
  } else if (cell.map->allFull()) {
    cell.state = CellState::kSolid;
    cell.map.reset();
    cell.pending.reset();
    cell.volume = cell.boxVolume();
  }
}

// The common case: the cell's own direction still holds the cut.
bool fastCutCell(Cell& cell, const CutContext& ctx) {
  // Lazy crossings need the cells' volumes stale anyway (no per-step volumes) and a
  // z map, whose z lines (the probes') are its parent heights alone.
  const ThreeMap& m = *cell.map;
  if (m.hasFlips()) return false;  // columns on both sides: twoSidedCutCell's
  if (ctx.lazySolid && !ctx.volumes && m.threeWay() && m.axis() == 2) {
    if (!cell.pending) cell.pending = std::make_unique<PendingCuts>();
    bool columns = false;
    const FastCut r =
        fastCutLazy(*cell.map, ctx.cache, ctx.reach, ctx.lazySolid, *cell.pending, &columns);
    if (r == FastCut::kOverhang) return false;
    if (r == FastCut::kDone) {
      cell.volume = kStaleVolume;
      ctx.counters.touched = true;
      ctx.counters.removes = ctx.counters.removes || columns;
    }
    return true;
  }
  settlePending(cell, ctx.grid);
  double delta = 0.0;
  bool columns = false;
  const FastCut r =
      fastCut(*cell.map, ctx.cache, ctx.reach, ctx.volumes ? &delta : nullptr, &columns);
  if (r == FastCut::kOverhang) return false;
  if (r == FastCut::kDone) {
    // A z map's moved crossings alone do not count, lazy or not (CutCounters::removes).
    ctx.counters.removes = ctx.counters.removes || columns || m.axis() != 2;
    if (ctx.volumes)
      setVolume(cell, cell.volume + delta, ctx);
    else
      cell.volume = kStaleVolume;
    ctx.counters.touched = true;
  }
  return true;
}

// A two-sided map (no fast path) whose direction still holds the cut: only the
// columns under the tool unpacked (two_sided_cut.h). False: the slow path's.
bool twoSidedCutCell(Cell& cell, const CutContext& ctx) {
  if (!cell.map->hasFlips()) return false;
  double delta = 0.0;
  const TwoSidedCut r =
      twoSidedCut(*cell.map, ctx.cache, ctx.reach, ctx.volumes ? &delta : nullptr);
  if (r == TwoSidedCut::kInvalid) return false;
  if (r == TwoSidedCut::kDone) {
    ctx.counters.touched = true;
    ctx.counters.removes = true;
    ctx.counters.slowCuts += 1;  // batches stay one-sided (Stock::cutIfFast)
    if (ctx.volumes)
      setVolume(cell, cell.volume + delta, ctx);
    else
      cell.volume = kStaleVolume;
  }
  return true;
}

// Picks, among the valid directions, the one closest to the tool's axis.
bool validDirection(const GoodBadMap (&maps)[3], const glm::dvec3& t, bool twoSided,
                    Direction& out) {
  bool found = false;
  for (int a = 0; a < 3; ++a) {
    if (!maps[a].valid(twoSided)) continue;
    if (!found || std::abs(t[a]) > std::abs(t[out.axis])) out = maps[a].validDirection();
    found = true;
  }
  return found;
}

// Calls f(i) for every solid vertex that lies beyond a gap when each line of
// direction d is walked from its base face: the vertices a heightmap in d cannot hold.
template <class F>
void forEachVertexBeyondGap(const SampleGrid& g, Direction d, F&& f) {
  const int a = d.axis, n = g.size(a);
  const GridBox& b = g.box();
  for (int cv = b.lo[axisV(a)]; cv <= b.hi[axisV(a)]; ++cv)
    for (int cu = b.lo[axisU(a)]; cu <= b.hi[axisU(a)]; ++cu) {
      std::array<int, 3> p{};
      p[a] = b.lo[a];
      p[axisU(a)] = cu;
      p[axisV(a)] = cv;
      const std::size_t i0 = g.index(p);
      bool gap = false;
      for (int k = 0; k < n; ++k) {
        const std::size_t i = i0 + (d.sign > 0 ? k : n - 1 - k) * g.stride(a);
        if (!g.solidAt(i))
          gap = true;
        else if (gap)
          f(i);
      }
    }
}

// An unsplittable (one cube) cell that no direction holds: drop the fewest
// solid vertices that make one direction hold it. They are cut out as a
// VertexDrops solid, here and (Stock::cut) in every other cell holding them,
// so all of them agree; a loss of a sliver around each vertex.
void forceFunctional(SampleGrid& g, const glm::dvec3& t, const CutContext& ctx) {
  int bestCount = -1;
  Direction best;
  for (int index = 0; index < 6; ++index) {
    const Direction d = directionFromIndex(index);
    int drop = 0;
    forEachVertexBeyondGap(g, d, [&](std::size_t) { ++drop; });
    const bool closer = std::abs(t[d.axis]) > std::abs(t[best.axis]);
    if (bestCount < 0 || drop < bestCount || (drop == bestCount && closer)) {
      bestCount = drop;
      best = d;
    }
  }
  std::vector<std::array<int, 3>> drops;
  const GridBox& b = g.box();
  forEachVertexBeyondGap(g, best, [&](std::size_t i) {
    const int nx = g.size(0), ny = g.size(1);
    const int x = static_cast<int>(i % nx), y = static_cast<int>(i / nx % ny),
              z = static_cast<int>(i / nx / ny);
    drops.push_back({b.lo[0] + x, b.lo[1] + y, b.lo[2] + z});
  });
  const VertexDrops solid(ctx.grid, drops);
  const IntervalCache cache(ctx.grid, solid);
  g.applyCut(cache);
  ctx.counters.dropped.insert(ctx.counters.dropped.end(), drops.begin(), drops.end());
  ctx.counters.forcedCells += 1;
  ctx.counters.forcedVertices += bestCount;
}

std::vector<SplitCandidate> splitCandidates(const SampleGrid& g, const GoodBadMap (&maps)[3],
                                            int oldAxis, const GridBox& box) {
  std::vector<SplitCandidate> out;
  for (const GoodBadMap& m : maps) isolationSplits(m, oldAxis, box, out);
  for (const GoodBadMap& m : maps) directSplits(g, m, box, out);
  auto key = [](const SplitCandidate& c) {
    return std::tuple(c.axis, c.lo, c.hi, int(c.type), c.complete, c.sole);
  };
  // Nothing the thesis's split types can offer (conflicting lines one grid
  // step apart): planes along a line that separate its crossings.
  if (out.empty())
    for (const GoodBadMap& m : maps) crossingSplits(g, m, box, out);
  std::sort(out.begin(), out.end(), [&](auto& x, auto& y) { return key(x) < key(y); });
  out.erase(std::unique(out.begin(), out.end(), [&](auto& x, auto& y) { return key(x) == key(y); }),
            out.end());
  if (out.empty()) {
    // Not even that (crossings on the same edge): halve the longest side so
    // the recursion still ends.
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (box.cubes(a) > box.cubes(axis)) axis = a;
    if (box.cubes(axis) >= 2)
      out.push_back({axis, box.lo[axis] + 1, box.hi[axis] - 1, SplitType::kFallback, false, false});
  }
  return out;
}

void split(Cell& cell, const SplitCandidate& c, int plane, const CutContext& ctx) {
  for (int side = 0; side < 2; ++side) {
    auto child = std::make_unique<Cell>();
    child->box = cell.box;
    (side == 0 ? child->box.hi : child->box.lo)[c.axis] = plane;
    child->id = mixHash(cell.id, side + 1);
    child->state = CellState::kPartial;
    child->map = std::make_unique<ThreeMap>(cell.map->restrictedTo(child->box));
    child->volume = child->map->volume();
    normalize(*child);
    cell.child[side] = std::move(child);
  }
  // Trapezoid sums are additive, so this moves only rounding noise.
  ctx.counters.removed += cell.volume - (cell.child[0]->volume + cell.child[1]->volume);
  cell.volume = 0.0;  // inner nodes hold no volume of their own
  cell.splitAxis = c.axis;
  cell.splitAt = plane;
  cell.map.reset();
  cell.state = CellState::kInner;
  ctx.counters.splits[static_cast<int>(c.type)] += 1;
}

void slowCut(Cell& cell, const CutContext& ctx, bool fresh) {
  const Direction old = cell.map->direction();
  SampleGrid g = SampleGrid::decode(*cell.map, cell.box);
  g.applyCut(ctx.cache, &ctx.reach);
  // A two-sided map comes here when a column under the tool holds two crossings
  // (twoSidedCutCell): only a new direction or a split is an overhang event then.
  const bool twoSidedCell = cell.map->hasFlips();
  if (twoSidedCell && !g.changed()) return;
  ctx.counters.slowCuts += 1;
  ctx.counters.touched = true;
  ctx.counters.removes = true;  // the cut removed what held the old surface
  markUnresolved(g, old, cell.map.get(), ctx.twoSided);
  const GoodBadMap maps[3] = {buildGoodBadMap(g, 0), buildGoodBadMap(g, 1), buildGoodBadMap(g, 2)};
  Direction d;
  if (validDirection(maps, ctx.toolDirection, ctx.twoSided, d)) {
    *cell.map = encodeMap(g, d, ctx.threeWay, ctx.twoSided);
    setVolume(cell, cell.map->volume(), ctx);
    if (!(twoSidedCell && d == old)) {
      if (fresh) ctx.counters.overhangEvents += 1;
      ctx.counters.resamples += 1;
    }
    return;
  }
  if (fresh) ctx.counters.overhangEvents += 1;
  const auto candidates = splitCandidates(g, maps, old.axis, cell.box);
  if (candidates.empty()) {
    forceFunctional(g, ctx.toolDirection, ctx);
    const GoodBadMap forced[3] = {buildGoodBadMap(g, 0), buildGoodBadMap(g, 1),
                                  buildGoodBadMap(g, 2)};
    if (!validDirection(forced, ctx.toolDirection, ctx.twoSided, d))
      throw std::logic_error("mdh: forcing a one-cube cell functional failed");
    *cell.map = encodeMap(g, d, ctx.threeWay, ctx.twoSided);
    setVolume(cell, cell.map->volume(), ctx);
    return;
  }
  SelectionContext sel{cell.box, ctx.toolDirection, ctx.toolRadius,
                       mixHash(mixHash(ctx.seed, cell.id), ctx.step)};
  const SplitCandidate& c = candidates[chooseSplit(candidates, ctx.rules, sel)];
  split(cell, c, planeFor(c, cell.box), ctx);
}

// The context for a child of a cell: its reach clipped to the solid and the fresh
// region again (a child is smaller than its parent: so may be the solid inside it).
CutContext within(const Cell& child, const CutContext& ctx) {
  CutContext c = ctx;
  c.reach = cutReach(ctx.grid, child.box.intersect(ctx.reach), ctx.cache.solid(), ctx.fresh);
  return c;
}

// A solid cell's first cut, when the guessed direction `d` cannot hold it: the other
// directions on the fast path, `d`'s opposite first (a tilted tool's flutes leave
// material above them), then the other axes by the tool's component, its sign first.
// A solid map costs nothing to make and a failing fast cut stops at its first
// overhanging column, so this is far cheaper than unpacking the cell (slowCut), which
// would pick one of these directions anyway (validDirection) when one holds. Counted
// as the overhang event and resample slowCut would count. False: none holds (the
// cell keeps a solid map in `d` for slowCut).
bool firstCutElsewhere(Cell& cell, const CutContext& ctx, Direction d, bool fresh) {
  std::array<Direction, 5> order;
  std::size_t n = 0;
  order[n++] = Direction{d.axis, -d.sign};
  int others[2] = {(d.axis + 1) % 3, (d.axis + 2) % 3};
  if (std::abs(ctx.toolDirection[others[1]]) > std::abs(ctx.toolDirection[others[0]]))
    std::swap(others[0], others[1]);
  for (int a : others) {
    const int sign = ctx.toolDirection[a] < 0.0 ? -1 : 1;
    order[n++] = Direction{a, sign};
    order[n++] = Direction{a, -sign};
  }
  for (const Direction& other : order) {
    *cell.map = ThreeMap(cell.box, other, ctx.threeWay);
    if (fastCutCell(cell, ctx)) {
      if (fresh) ctx.counters.overhangEvents += 1;
      ctx.counters.resamples += 1;
      ctx.counters.touched = true;
      ctx.counters.removes = true;
      return true;
    }
  }
  *cell.map = ThreeMap(cell.box, d, ctx.threeWay);
  return false;
}

void cutLeaf(Cell& cell, const CutContext& ctx, bool fresh) {
  if (cell.state == CellState::kEmpty || cell.box.intersect(ctx.reach).empty()) return;
  bool done = false;
  if (cell.state == CellState::kSolid) {
    // Probe first: most solid cells under the tool's box lose nothing.
    if (!toolRemovesSomeVertex(cell.box.intersect(ctx.reach), ctx.cache)) return;
    const Direction d = guessDirection(ctx.toolDirection);
    cell.map = std::make_unique<ThreeMap>(cell.box, d, ctx.threeWay);
    cell.state = CellState::kPartial;
    done = fastCutCell(cell, ctx) || firstCutElsewhere(cell, ctx, d, fresh);
  } else {
    done = fastCutCell(cell, ctx) || twoSidedCutCell(cell, ctx);
  }
  if (!done) {
    settlePending(cell, ctx.grid);  // the slow path reads every crossing
    slowCut(cell, ctx, fresh);
  }
  if (cell.state == CellState::kInner) {
    for (auto& child : cell.child) cutLeaf(*child, within(*child, ctx), false);
    return;
  }
  normalize(cell);
}

}  // namespace

LazyPlan planLazyCut(const Cell& brick, const CutContext& ctx) {
  LazyPlan plan;
  if (brick.state == CellState::kEmpty || brick.box.intersect(ctx.reach).empty()) return plan;
  plan.kind = LazyPlan::Kind::kOther;
  if (brick.state == CellState::kInner || !ctx.lazySolid || ctx.volumes || !ctx.threeWay)
    return plan;
  const ThreeMap* map = brick.map.get();
  if (brick.state == CellState::kSolid) {
    // As cutLeaf: most solid cells under the tool's box lose nothing.
    if (!toolRemovesSomeVertex(brick.box.intersect(ctx.reach), ctx.cache)) {
      plan.kind = LazyPlan::Kind::kNothing;
      return plan;
    }
    const Direction d = guessDirection(ctx.toolDirection);
    if (d.axis != 2) return plan;
    plan.map = std::make_unique<ThreeMap>(brick.box, d, ctx.threeWay);
    map = plan.map.get();
  } else if (!map->threeWay() || map->axis() != 2 || map->hasFlips()) {
    return plan;
  }
  switch (lazyColumns(*map, ctx.cache, ctx.reach, plan.changes)) {
    case FastCut::kUnchanged:
      plan.kind = LazyPlan::Kind::kNothing;
      break;
    case FastCut::kDone:
      plan.kind = LazyPlan::Kind::kCut;
      break;
    case FastCut::kOverhang:
      plan.kind = LazyPlan::Kind::kRefuse;
      break;
  }
  return plan;
}

void cutPlanned(Cell& brick, LazyPlan& plan, const CutContext& ctx) {
  if (plan.kind != LazyPlan::Kind::kCut) return;
  if (plan.map) {
    brick.map = std::move(plan.map);
    brick.state = CellState::kPartial;
  }
  if (!brick.pending) brick.pending = std::make_unique<PendingCuts>();
  cutLazily(*brick.map, ctx.cache, ctx.reach, plan.changes, ctx.lazySolid, *brick.pending);
  brick.volume = kStaleVolume;
  ctx.counters.touched = true;
  ctx.counters.removes = ctx.counters.removes || !plan.changes.empty();
  normalize(brick);
#ifndef NDEBUG
  checkCell(brick);
#endif
}

void cutCell(Cell& cell, const CutContext& ctx) {
  if (cell.state == CellState::kEmpty || cell.box.intersect(ctx.reach).empty()) return;
  if (cell.state == CellState::kInner) {
    for (auto& child : cell.child) cutCell(*child, within(*child, ctx));
    return;
  }
  cutLeaf(cell, ctx, true);
#ifndef NDEBUG
  checkCell(cell);
#endif
}

namespace {

[[noreturn]] void fail(const Cell& cell, const std::string& what) {
  const GridBox& b = cell.box;
  throw std::logic_error("mdh invariant: cell [" + std::to_string(b.lo[0]) + "," +
                         std::to_string(b.lo[1]) + "," + std::to_string(b.lo[2]) + "]-[" +
                         std::to_string(b.hi[0]) + "," + std::to_string(b.hi[1]) + "," +
                         std::to_string(b.hi[2]) + "]: " + what);
}

void checkMap(const Cell& cell) {
  const ThreeMap& m = *cell.map;
  if (!(m.box() == cell.box)) fail(cell, "heightmap box differs from the cell box");
  const int a = m.axis(), lo = cell.box.lo[a], hi = cell.box.hi[a];
  for (int iv = 0; iv < m.columnsV(); ++iv)
    for (int iu = 0; iu < m.columnsU(); ++iu) {
      const double h = m.height(iu, iv);
      const bool empty = m.columnUp(iu, iv) ? h == -kInf : h == kInf;
      if (!empty && !(h >= lo && h <= hi)) fail(cell, "parent height outside the cell");
      const int n = m.columnCount(iu, iv);
      if (m.flipped(iu, iv) && (n == 0 || n == m.levels()))
        fail(cell, "a full or empty column is flipped");
    }
  if (!std::isnan(cell.volume) &&
      std::abs(m.volume() - cell.volume) > 1e-6 * (1.0 + cell.boxVolume()))
    fail(cell, "cached volume differs from the heightmap's");
  if (!m.threeWay()) return;
  for (int family = 0; family < 2; ++family)
    for (int r = 0; r < m.rowCount(family); ++r) {
      std::size_t expected = 0;
      const auto& row = m.row(family, r);
      for (int e = 0; e < m.edgesInRow(family); ++e) {
        const int count = m.straddleEdge(family, r, e).total();
        const int base = cell.box.lo[family == 0 ? m.uAxis() : m.vAxis()] + e;
        for (int i = 0; i < count; ++i) {
          if (expected + i >= row.size()) fail(cell, "embedded row too short");
          const double x = row[expected + i];
          if (std::isnan(x) && cell.pending) continue;  // the pending cut's to compute
          if (!(x >= base && x <= base + 1)) fail(cell, "embedded height off its edge");
        }
        expected += count;
      }
      if (expected != row.size()) fail(cell, "embedded row has extra entries");
    }
}

}  // namespace

void checkCell(const Cell& cell) {
  switch (cell.state) {
    case CellState::kEmpty:
    case CellState::kSolid:
      if (cell.map) fail(cell, "solid/empty cell holds a grid");
      return;
    case CellState::kPartial:
      if (!cell.map) fail(cell, "partial cell without a heightmap");
      checkMap(cell);
      return;
    case CellState::kInner: {
      if (cell.map) fail(cell, "inner node holds a grid");
      const int a = cell.splitAxis;
      if (a < 0 || a > 2 || cell.splitAt <= cell.box.lo[a] || cell.splitAt >= cell.box.hi[a])
        fail(cell, "split plane not strictly inside");
      for (int side = 0; side < 2; ++side) {
        if (!cell.child[side]) fail(cell, "missing child");
        GridBox expect = cell.box;
        (side == 0 ? expect.hi : expect.lo)[a] = cell.splitAt;
        if (!(cell.child[side]->box == expect)) fail(cell, "child box does not tile the parent");
        checkCell(*cell.child[side]);
      }
      return;
    }
  }
}

}  // namespace mdhd::mdh

#pragma once
// The stock as a multidirectional heightmap (mdh-map): a kD-tree of cells over
// a uniform sampling grid, every partial cell a (3-way) heightmap in one of
// the six axis directions. The only way in is a LineSolid per in-between step.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/geometry/fresh_region.h"
#include "sim/geometry/line_solid.h"
#include "sim/mdh/cell.h"
#include "sim/mdh/cut_counters.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/line_segments.h"
#include "sim/mdh/split_rules.h"
#include "sim/mdh/stats.h"
#include "sim/mdh/worker_pool.h"

namespace mdhd::mdh {

class IntervalCache;
struct CutContext;

struct StockOptions {
  double density = 10.0;  // grid points per mm
  bool three_way = true;
  // Two-sided 3-maps (thesis 7.4, three_map.h): a column may hold its solid on the
  // far side, so a sign conflict alone no longer splits a cell. 3-maps only.
  bool two_sided = true;
  std::vector<Rule> ruleset{Rule::kFEFS_FFS, Rule::kCTD, Rule::kSPT, Rule::kRS};
  std::uint64_t seed = 1;
  int threads = 0;  // 0: hardware concurrency
  int brick = 32;   // pre-split into bricks of this many grid cubes; 0: one root cell
  // The bricks' size along z when it differs: -1 brick's, 0 the stock's height. A stock
  // only ever cut from above (a 3-axis machine) keeps +z maps: a brick as tall as the
  // stock holds a column in one map, with fewer cells to visit per step.
  int brick_z = -1;
  double tool_radius_hint = 0.0;  // mm, FEFS's threshold until setToolRadius
  // CutResult::removed_volume of every step. Off, a cut skips the edge integrals
  // of the volume change (a tenth of a 3-axis step) and reports 0; volume() is
  // exact either way (it integrates the maps, not the cells' cached volumes).
  bool step_volumes = true;
  // Crossings across a z map's columns computed when needed rather than by every
  // batch cut (cutIfFast with a shared solid, step_volumes off: lazy_crossings.h).
  // The same stock to the bit either way; off for comparing the two.
  bool lazy_crossings = true;
};

struct CutResult {
  double removed_volume = 0.0;  // mm^3, this step (0 unless StockOptions::step_volumes)
  bool touched = false;         // any material changed (or may have: a lazy cut into a z map)
  // Material surely changed: as touched, but a z map counts only where a column moved
  // (with lazy crossings or without, so the answer is the same either way).
  bool removed = false;
  bool overhang = false;  // some cell needed a new direction or a split
  std::int64_t overhang_events = 0;
  std::int64_t splits = 0;
};

struct Overlap {
  bool touched = false;     // overlaps material along some grid line by more than the tolerance
  double volume = 0.0;      // mm^3 of stock inside the solid (grid estimate)
  double max_length = 0.0;  // mm, longest overlap along one grid line
};

// Machined surface area by outward normal, as projections: by_direction[+a]
// is the integral of max(0, n.a) dA (the surface facing +a, projected along
// a), counted from the crossings of all grid lines (uncut stock faces are
// not counted). overhang = the -z entry: downward-facing surface projected
// on the xy plane, which no +z heightmap can hold. total = their sum (at
// most sqrt(3) times the true area).
struct SurfaceArea {
  std::array<double, 6> by_direction{};  // mm^2: +x -x +y -y +z -z
  double overhang = 0.0;
  double total = 0.0;
};

// Read-only view of a leaf for visitors (meshing, debugging).
struct LeafView {
  const GridBox& box;
  CellState state;
  const ThreeMap* map;  // null unless partial
};

// f(LeafView) for every leaf under `c` (c itself if it is one), in the tree's order.
template <class F>
void visitLeaves(const Cell& c, const F& f) {
  if (c.state == CellState::kInner) {
    visitLeaves(*c.child[0], f);
    visitLeaves(*c.child[1], f);
    return;
  }
  f(LeafView{c.box, c.state, c.map.get()});
}

class Stock {
 public:
  // Throws std::invalid_argument for an empty box, a non-positive density or a grid too large.
  Stock(const geom::Aabb& box, StockOptions options);
  // Why `box` and `options` cannot make a stock (the constructor's std::invalid_argument
  // text), or empty: for checking a job before it runs, without allocating the grid.
  static std::string gridProblem(const geom::Aabb& box, const StockOptions& options);
  ~Stock();
  Stock(const Stock&) = delete;
  Stock& operator=(const Stock&) = delete;

  // A deep copy (every cell and heightmap): a look-ahead cuts the copy while the
  // original goes on. Costs time and memory in proportion to the stock's cells.
  std::unique_ptr<Stock> clone() const;

  // Removes the solid; tool_direction points from the tool tip to the spindle.
  // `fresh`, when given, holds every point of the solid that an earlier cut has not
  // removed (geom::freshRegion: the previous step ended where this one starts):
  // bricks and grid lines outside it are not looked at. The result is the same to
  // the bit (line_segments.h, kToolSlack).
  CutResult cut(const geom::LineSolid& solid, const glm::dvec3& tool_direction,
                const geom::FreshRegion* fresh = nullptr);
  // The same with the solid shared: z maps the cut reaches keep it for the crossings
  // across their columns, computed later (StockOptions::lazy_crossings, as cutIfFast's
  // below); `touched` is then true wherever it reaches a partial z map.
  CutResult cut(std::shared_ptr<const geom::LineSolid> solid, const glm::dvec3& tool_direction,
                const geom::FreshRegion* fresh = nullptr);
  // The same cut, taken only when every cell it reaches stays in its direction
  // without a split (the fast path): otherwise the stock is left exactly as it was
  // and nothing is returned. The slow path's choices (a new direction, a split plane,
  // RS's seed) depend on the order of the steps, the fast path's heights and
  // crossings only on the union of what they remove: a union of `steps` consecutive
  // sweeps cut here leaves the stock those steps cut one by one would (but for a
  // crossing an edge gets from both ends, which the union may place elsewhere inside
  // the edge: tests/mdh/test_batched_cuts.cpp), and counts as that many steps. Costs a
  // copy of the bricks it reaches, kept for the undo.
  std::optional<CutResult> cutIfFast(const geom::LineSolid& solid, const glm::dvec3& tool_direction,
                                     const geom::FreshRegion* fresh, std::uint64_t steps);
  // The same with the solid shared: the cells may keep it for crossings they compute
  // later (StockOptions::lazy_crossings), which every query below settles first and
  // settle() computes at once, on the stock's threads. CutResult::touched is then true
  // whenever the cut reaches a partial z map. Where every brick reached is a z map (or
  // solid), the batch is planned on all of them before any is cut: no copies for an undo.
  std::optional<CutResult> cutIfFast(std::shared_ptr<const geom::LineSolid> solid,
                                     const glm::dvec3& tool_direction,
                                     const geom::FreshRegion* fresh, std::uint64_t steps);
  // Computes every pending crossing (a no-op when none is).
  void settle();
  void setToolRadius(double mm) { toolRadius_ = mm; }

  Overlap probe(const geom::LineSolid& solid, double tolerance = 0.0) const;
  // Whether a cut of `solid` would remove material along some z grid line of the
  // stock as it would be after cuts of `cutBefore` (not made yet): `solid`'s
  // intervals, less theirs, reaching into the solid by more than kToolSlack.
  // Only lines inside `region` (when given) are looked at, outwards from the one
  // nearest `first` (where it most likely removes); stops at the first such line and
  // puts it in `hit` (x, y, and the middle of what it removes there) when given.
  bool removesMaterial(const geom::LineSolid& solid, const geom::FreshRegion* region,
                       std::span<const geom::LineSolid* const> cutBefore, const glm::dvec3& first,
                       glm::dvec3* hit = nullptr) const;
  bool isSolid(const glm::dvec3& p) const;
  // Solid intervals (mm) along the grid line of `axis` through vertex indices
  // iu on axis (axis+1)%3 and iv on (axis+2)%3.
  void solidIntervals(int axis, int iu, int iv, std::vector<geom::Interval>& out) const;
  double volume() const;  // mm^3
  SurfaceArea area() const;
  Stats stats() const;
  // Throws std::logic_error naming the first broken invariant: a cell's own (heightmap
  // inside its box, cached volume, embedded rows) or two leaves disagreeing on a shared
  // vertex or edge (shared_samples.h).
  void checkInvariants() const;
  void forEachLeaf(const std::function<void(const LeafView&)>& visit) const;

  const GridSpec& grid() const { return grid_; }
  // The threads a cut runs on (StockOptions::threads, 0 resolved to the machine's).
  int threads() const { return threads_; }
  const StockOptions& options() const { return options_; }
  std::uint64_t steps() const { return step_; }

 private:
  int brickIndex(const std::array<int, 3>& b) const {
    return b[0] + bricks_[0] * (b[1] + bricks_[1] * b[2]);
  }
  struct CloneTag {};
  Stock(const Stock& other, CloneTag);
  const Cell* leafAt(const glm::dvec3& g) const;
  // One pass of a step over the bricks the cache reaches, on the workers.
  // `undo`, when given, receives the bricks cut and a copy of each as it was before.
  struct BrickUndo {
    std::vector<int> bricks;
    std::vector<Cell> before;
  };
  CutCounters cutBricks(IntervalCache& cache, const glm::dvec3& toolDirection,
                        const geom::FreshRegion* fresh, BrickUndo* undo = nullptr,
                        std::shared_ptr<const geom::LineSolid> lazySolid = nullptr);
  // The bricks a cut reaches (not empty, not outside the fresh region), their reach,
  // and the order to hand them to the workers in (largest reach first).
  void reachedBricks(const IntervalCache& cache, const geom::FreshRegion* fresh,
                     std::vector<int>& items, std::vector<GridBox>& reach,
                     std::vector<std::size_t>& order) const;
  // What cut_cell.h needs to cut one brick (its reach, counters and the lazy solid).
  CutContext brickContext(const IntervalCache& cache, const GridBox& reach,
                          const geom::FreshRegion* fresh, const glm::dvec3& toolDirection,
                          CutCounters& counters,
                          const std::shared_ptr<const geom::LineSolid>& lazySolid) const;
  // work(0 .. count-1) on the workers when the cut is large enough to pay for them.
  void runOnBricks(IntervalCache& cache, std::size_t count,
                   const std::function<void(std::size_t)>& work);
  // A lazy batch planned on every brick first (cut_cell.h's LazyPlan), then cut.
  enum class LazyBatch { kTaken, kRefused, kOther };
  LazyBatch cutLazyBatch(IntervalCache& cache, const glm::dvec3& toolDirection,
                         const geom::FreshRegion* fresh,
                         const std::shared_ptr<const geom::LineSolid>& lazySolid,
                         CutCounters& step);
  // Whether a cut with a shared solid leaves z maps' crossings pending.
  bool lazyCrossings() const {
    return options_.lazy_crossings && options_.three_way && !options_.step_volumes;
  }
  CutResult cutWith(const geom::LineSolid& solid, std::shared_ptr<const geom::LineSolid> lazySolid,
                    const glm::dvec3& toolDirection, const geom::FreshRegion* fresh);
  std::optional<CutResult> cutIfFastWith(const geom::LineSolid& solid,
                                         std::shared_ptr<const geom::LineSolid> lazySolid,
                                         const glm::dvec3& toolDirection,
                                         const geom::FreshRegion* fresh, std::uint64_t steps);
  // Settles pending crossings before a query reads the maps: logically const (the
  // stock's solid is the same before and after), serialised for queries made from
  // several threads at once.
  void ensureSettled() const;
  void settleBricks(int workers);
  // work(b) for every brick b, on the stock's threads in bands of bricks (threads of
  // their own, not the pool: a const query may run on any thread, several at once,
  // or on the pool itself). For whole-stock sums kept per brick, added in brick order.
  void onBrickBands(const std::function<void(std::size_t)>& work) const;
  CutResult result(const CutCounters& step) const;
  // Solid segments (grid units, merged across cells) of one grid line.
  void gridLineSegments(int axis, int iu, int iv, std::vector<Span>& out) const;

  StockOptions options_;
  GridSpec grid_;
  std::array<int, 3> bricks_{1, 1, 1};
  int brickSize_[3]{};
  std::vector<Cell> roots_;
  CutCounters totals_;
  std::unique_ptr<LineStore> lines_ = std::make_unique<LineStore>();  // reused by every cut
  std::unique_ptr<WorkerPool> pool_;  // made on the first cut that uses two threads or more
  std::uint64_t step_ = 0;
  double toolRadius_ = 0.0;
  int threads_ = 1;
  // Whether some cell may hold a pending cut (set by lazy cuts, cleared by settle).
  std::atomic<bool> pending_{false};
  mutable std::mutex settleMutex_;
};

}  // namespace mdhd::mdh

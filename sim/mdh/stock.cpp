#include "sim/mdh/stock.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sim/mdh/cut_cell.h"
#include "sim/mdh/cut_reach.h"
#include "sim/mdh/interval_cache.h"
#include "sim/mdh/lazy_crossings.h"
#include "sim/mdh/rng.h"
#include "sim/mdh/shared_samples.h"
#include "sim/mdh/vertex_drops.h"
#include "sim/mdh/worker_pool.h"

namespace mdhd::mdh {

namespace {

constexpr int kMaxCubesPerAxis = 1 << 20;
constexpr std::int64_t kMaxBricks = std::int64_t{1} << 22;
constexpr double kMaxCellPoints = 257.0 * 257.0 * 257.0;
constexpr char kAxisNames[] = "xyz";

// A missing or broken tool axis only weakens the direction guesses and CTD.
glm::dvec3 usableDirection(const glm::dvec3& d) {
  if (!std::isfinite(d.x + d.y + d.z) || d == glm::dvec3(0.0)) return {0.0, 0.0, 1.0};
  return d;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f", x);
  return text;
}

// Too fine a grid: what the job can change is the density (the brick is check's).
std::string gridMessage(const std::string& what, double density) {
  char text[64];
  std::snprintf(text, sizeof text, "mdh: at %g points/mm ", density);
  return text + what + ": lower the density";
}

// The grid and bricks a box and options give, or why they cannot make a stock.
struct GridPlan {
  int cubes[3]{};
  int brickSize[3]{};
  int bricks[3]{};
  std::int64_t brickCount = 1;
  std::string problem;  // empty: usable
};

GridPlan planGrid(const geom::Aabb& box, const StockOptions& o) {
  GridPlan plan;
  if (!(o.density > 0.0) || !std::isfinite(o.density)) {
    plan.problem = "mdh: density must be a positive number of grid points per mm";
    return plan;
  }
  if (o.brick < 0 || o.brick_z < -1) {
    plan.problem = o.brick < 0 ? "mdh: brick size must be >= 0" : "mdh: brick_z must be >= -1";
    return plan;
  }
  const double h = 1.0 / o.density;
  for (int a = 0; a < 3; ++a) {
    const double extent = box.hi[a] - box.lo[a];
    if (!(extent > 0.0) || !std::isfinite(extent)) {
      plan.problem = std::string("mdh: stock box is empty or invalid along ") + kAxisNames[a];
      return plan;
    }
    // The max corner snaps to the nearest grid plane.
    const double cubes = std::max(1.0, std::round(extent / h));
    if (cubes > kMaxCubesPerAxis) {
      plan.problem = gridMessage("the stock is " + number(cubes) + " grid cubes along " +
                                     kAxisNames[a] + ", more than " + number(kMaxCubesPerAxis),
                                 o.density);
      return plan;
    }
    plan.cubes[a] = static_cast<int>(cubes);
    const int size = a == 2 && o.brick_z >= 0 ? o.brick_z : o.brick;
    plan.brickSize[a] = size > 0 ? size : plan.cubes[a];
    plan.bricks[a] = (plan.cubes[a] + plan.brickSize[a] - 1) / plan.brickSize[a];
    plan.brickCount *= plan.bricks[a];
  }
  // An overhang unpacks a whole cell (about 25 bytes per vertex), so the
  // largest cell is bounded.
  double cellPoints = 1.0;
  for (int a = 0; a < 3; ++a) cellPoints *= std::min(plan.brickSize[a], plan.cubes[a]) + 1.0;
  if (cellPoints > kMaxCellPoints) {
    plan.problem = "mdh: cells of " + number(cellPoints) +
                   " grid points are too large to unpack; use a brick size of at most 256 (or "
                   "a coarser density)";
  } else if (plan.brickCount > kMaxBricks) {
    plan.problem = gridMessage("the stock's grid of " + number(plan.cubes[0]) + " x " +
                                   number(plan.cubes[1]) + " x " + number(plan.cubes[2]) +
                                   " cubes needs " + number(double(plan.brickCount)) +
                                   " bricks, more than " + number(double(kMaxBricks)),
                               o.density);
  }
  return plan;
}

}  // namespace

std::string Stock::gridProblem(const geom::Aabb& box, const StockOptions& options) {
  return planGrid(box, options).problem;
}

Stock::Stock(const geom::Aabb& box, StockOptions options) : options_(std::move(options)) {
  const GridPlan plan = planGrid(box, options_);
  if (!plan.problem.empty()) throw std::invalid_argument(plan.problem);
  grid_.origin = box.lo;
  grid_.h = 1.0 / options_.density;
  for (int a = 0; a < 3; ++a) {
    grid_.cubes[a] = plan.cubes[a];
    brickSize_[a] = plan.brickSize[a];
    bricks_[a] = plan.bricks[a];
  }
  const std::int64_t bricks = plan.brickCount;
  roots_.resize(static_cast<std::size_t>(bricks));
  for (int z = 0; z < bricks_[2]; ++z)
    for (int y = 0; y < bricks_[1]; ++y)
      for (int x = 0; x < bricks_[0]; ++x) {
        Cell& c = roots_[brickIndex({x, y, z})];
        const std::array<int, 3> b{x, y, z};
        for (int a = 0; a < 3; ++a) {
          c.box.lo[a] = b[a] * brickSize_[a];
          c.box.hi[a] = std::min(grid_.cubes[a], (b[a] + 1) * brickSize_[a]);
        }
        c.id = mixHash(0x6d64686d6170ULL, static_cast<std::uint64_t>(brickIndex(b)));
        c.state = CellState::kSolid;
        c.volume = c.boxVolume();
      }
  const unsigned hw = std::thread::hardware_concurrency();
  threads_ = options_.threads > 0 ? options_.threads : static_cast<int>(std::max(1u, hw));
  toolRadius_ = options_.tool_radius_hint;
}

Stock::~Stock() = default;

CutResult Stock::cut(const geom::LineSolid& solid, const glm::dvec3& toolDirection,
                     const geom::FreshRegion* fresh) {
  return cutWith(solid, nullptr, toolDirection, fresh);
}

CutResult Stock::cut(std::shared_ptr<const geom::LineSolid> solid, const glm::dvec3& toolDirection,
                     const geom::FreshRegion* fresh) {
  const geom::LineSolid& s = *solid;
  return cutWith(s, lazyCrossings() ? std::move(solid) : nullptr, toolDirection, fresh);
}

CutResult Stock::cutWith(const geom::LineSolid& solid,
                         std::shared_ptr<const geom::LineSolid> lazySolid,
                         const glm::dvec3& toolDirection, const geom::FreshRegion* fresh) {
  ++step_;
  const glm::dvec3 tool_direction = usableDirection(toolDirection);
  IntervalCache cache(grid_, solid, lines_.get());
  if (cache.touched().empty()) return {};
  const bool lazy = lazySolid != nullptr;
  CutCounters step = cutBricks(cache, tool_direction, fresh, nullptr, std::move(lazySolid));
  if (lazy) pending_.store(true, std::memory_order_release);
  // Vertices forced cells dropped are cut out of every other cell holding
  // them (which may force more): neighbours keep one state per vertex.
  for (std::vector<std::array<int, 3>> dropped; !step.dropped.empty();) {
    dropped.swap(step.dropped);
    step.dropped.clear();
    const VertexDrops drops(grid_, dropped);
    IntervalCache dropCache(grid_, drops);
    step.add(cutBricks(dropCache, tool_direction, nullptr));
  }
  totals_.add(step);
  return result(step);
}

CutResult Stock::result(const CutCounters& step) const {
  CutResult result;
  const double h3 = grid_.h * grid_.h * grid_.h;
  result.removed_volume = options_.step_volumes ? step.removed * h3 : 0.0;
  result.touched = step.touched;
  result.removed = step.removes;
  result.overhang_events = step.overhangEvents;
  result.overhang = step.overhangEvents > 0;
  for (auto s : step.splits) result.splits += s;
  return result;
}

std::optional<CutResult> Stock::cutIfFast(const geom::LineSolid& solid,
                                          const glm::dvec3& toolDirection,
                                          const geom::FreshRegion* fresh, std::uint64_t steps) {
  return cutIfFastWith(solid, nullptr, toolDirection, fresh, steps);
}

std::optional<CutResult> Stock::cutIfFast(std::shared_ptr<const geom::LineSolid> solid,
                                          const glm::dvec3& toolDirection,
                                          const geom::FreshRegion* fresh, std::uint64_t steps) {
  const geom::LineSolid& s = *solid;
  return cutIfFastWith(s, lazyCrossings() ? std::move(solid) : nullptr, toolDirection, fresh,
                       steps);
}

std::optional<CutResult> Stock::cutIfFastWith(const geom::LineSolid& solid,
                                              std::shared_ptr<const geom::LineSolid> lazySolid,
                                              const glm::dvec3& toolDirection,
                                              const geom::FreshRegion* fresh, std::uint64_t steps) {
  const glm::dvec3 tool_direction = usableDirection(toolDirection);
  IntervalCache cache(grid_, solid, lines_.get());
  if (cache.touched().empty()) {
    step_ += steps;
    return CutResult{};
  }
  ++step_;
  const bool lazy = lazySolid != nullptr;
  if (lazy) {
    // Planned first, cut after: a batch that some brick cannot take on the fast path
    // is refused before any brick changes, with no copies to undo.
    CutCounters step;
    switch (cutLazyBatch(cache, tool_direction, fresh, lazySolid, step)) {
      case LazyBatch::kTaken:
        pending_.store(true, std::memory_order_release);
        step_ += steps - 1;
        totals_.add(step);
        return result(step);
      case LazyBatch::kRefused:
        --step_;
        return std::nullopt;
      case LazyBatch::kOther:
        break;  // a brick needs more than a z map: cut with undo copies as below
    }
  }
  // Every new direction counts an overhang event at the leaf it starts from and
  // every slow cut that changes its leaf a slow cut (cut_cell.cpp); vertex drops
  // follow only from slow cuts.
  BrickUndo undo;
  const CutCounters step = cutBricks(cache, tool_direction, fresh, &undo, std::move(lazySolid));
  if (step.overhangEvents > 0 || step.slowCuts > 0 || !step.dropped.empty()) {
    for (std::size_t i = 0; i < undo.bricks.size(); ++i)
      roots_[static_cast<std::size_t>(undo.bricks[i])] = std::move(undo.before[i]);
    --step_;
    return std::nullopt;
  }
  if (lazy) pending_.store(true, std::memory_order_release);
  step_ += steps - 1;
  totals_.add(step);
  return result(step);
}

namespace {

void settleSubtree(Cell& cell, const GridSpec& grid) {
  if (cell.state == CellState::kInner) {
    for (auto& child : cell.child) settleSubtree(*child, grid);
    return;
  }
  settlePending(cell, grid);
}

}  // namespace

void Stock::settleBricks(int workers) {
  std::vector<std::size_t> due;
  for (std::size_t i = 0; i < roots_.size(); ++i)
    if (roots_[i].state == CellState::kInner || roots_[i].pending) due.push_back(i);
  const std::function<void(std::size_t)> work = [&](std::size_t k) {
    settleSubtree(roots_[due[k]], grid_);
  };
  if (workers > 1 && due.size() > 1) {
    if (!pool_) pool_ = std::make_unique<WorkerPool>(threads_);
    pool_->run(due.size(), workers, work);
  } else {
    for (std::size_t k = 0; k < due.size(); ++k) work(k);
  }
  pending_.store(false, std::memory_order_release);
}

void Stock::settle() {
  if (!pending_.load(std::memory_order_acquire)) return;
  const std::lock_guard lock(settleMutex_);
  if (pending_.load(std::memory_order_acquire)) settleBricks(threads_);
}

void Stock::ensureSettled() const {
  if (!pending_.load(std::memory_order_acquire)) return;
  const std::lock_guard lock(settleMutex_);
  // One thread, on this one: the query may itself run on the stock's workers.
  if (pending_.load(std::memory_order_acquire)) const_cast<Stock*>(this)->settleBricks(1);
}

void Stock::reachedBricks(const IntervalCache& cache, const geom::FreshRegion* fresh,
                          std::vector<int>& items, std::vector<GridBox>& reach,
                          std::vector<std::size_t>& order) const {
  const GridBox& t = cache.touched();
  items.clear();
  reach.clear();
  std::array<int, 3> first{}, last{};
  for (int a = 0; a < 3; ++a) {
    first[a] = std::max(0, (t.lo[a] - 1) / brickSize_[a]);
    last[a] = std::min(bricks_[a] - 1, t.hi[a] / brickSize_[a]);
  }
  for (int z = first[2]; z <= last[2]; ++z)
    for (int y = first[1]; y <= last[1]; ++y)
      for (int x = first[0]; x <= last[0]; ++x) {
        const int i = brickIndex({x, y, z});
        if (roots_[i].state == CellState::kEmpty) continue;
        const GridBox r = cutReach(grid_, roots_[i].box.intersect(t), cache.solid(), fresh);
        if (r.empty()) continue;  // nothing there the earlier cuts left
        items.push_back(i);
        reach.push_back(r);
      }
  // Largest reach first, so two threads do not end a step with one big brick left
  // to one of them (the order is the data's, so the sums below do not depend on
  // the thread count).
  order.resize(items.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t l, std::size_t r) {
    return reach[l].pointCount() > reach[r].pointCount();
  });
}

Stock::LazyBatch Stock::cutLazyBatch(IntervalCache& cache, const glm::dvec3& tool_direction,
                                     const geom::FreshRegion* fresh,
                                     const std::shared_ptr<const geom::LineSolid>& lazySolid,
                                     CutCounters& step) {
  std::vector<int> items;
  std::vector<GridBox> reach;
  std::vector<std::size_t> order;
  reachedBricks(cache, fresh, items, reach, order);
  std::vector<CutCounters> counters(items.size());
  std::vector<LazyPlan> plans(items.size());
  const auto context = [&](std::size_t i) {
    return brickContext(cache, reach[i], fresh, tool_direction, counters[i], lazySolid);
  };
  const std::function<void(std::size_t)> plan = [&](std::size_t k) {
    const std::size_t i = order[k];
    plans[i] = planLazyCut(roots_[items[i]], context(i));
  };
  const std::function<void(std::size_t)> cut = [&](std::size_t k) {
    const std::size_t i = order[k];
    cutPlanned(roots_[items[i]], plans[i], context(i));
  };
  runOnBricks(cache, items.size(), plan);
  bool refused = false;
  for (const LazyPlan& p : plans) {
    if (p.kind == LazyPlan::Kind::kOther) return LazyBatch::kOther;
    refused = refused || p.kind == LazyPlan::Kind::kRefuse;
  }
  if (refused) return LazyBatch::kRefused;
  runOnBricks(cache, items.size(), cut);
  for (const CutCounters& c : counters) step.add(c);  // fixed order: identical sums
  return LazyBatch::kTaken;
}

CutContext Stock::brickContext(const IntervalCache& cache, const GridBox& reach,
                               const geom::FreshRegion* fresh, const glm::dvec3& toolDirection,
                               CutCounters& counters,
                               const std::shared_ptr<const geom::LineSolid>& lazySolid) const {
  return CutContext{grid_,
                    cache,
                    reach,
                    fresh,
                    options_.ruleset,
                    options_.step_volumes,
                    options_.three_way,
                    options_.three_way && options_.two_sided,
                    toolDirection,
                    toolRadius_ / grid_.h,
                    options_.seed,
                    step_,
                    counters,
                    lazySolid};
}

void Stock::runOnBricks(IntervalCache& cache, std::size_t count,
                        const std::function<void(std::size_t)>& work) {
  // Waking a helper costs microseconds: small steps stay on this thread.
  constexpr std::int64_t kParallelPoints = 32768;
  const int workers = cache.touched().pointCount() < kParallelPoints ? 1 : threads_;
  const bool parallel = workers > 1 && count > 1;
  cache.setShared(parallel);
  if (parallel) {
    if (!pool_) pool_ = std::make_unique<WorkerPool>(threads_);
    pool_->run(count, workers, work);
  } else {
    for (std::size_t i = 0; i < count; ++i) work(i);
  }
}

CutCounters Stock::cutBricks(IntervalCache& cache, const glm::dvec3& tool_direction,
                             const geom::FreshRegion* fresh, BrickUndo* undo,
                             std::shared_ptr<const geom::LineSolid> lazySolid) {
  std::vector<int> items;
  std::vector<GridBox> reach;
  std::vector<std::size_t> order;
  reachedBricks(cache, fresh, items, reach, order);
  std::vector<CutCounters> counters(items.size());
  if (undo != nullptr) {
    undo->bricks = items;
    undo->before.resize(items.size());
  }
  const std::function<void(std::size_t)> work = [&](std::size_t k) {
    const std::size_t i = order[k];
    if (undo != nullptr) copyCell(roots_[items[i]], undo->before[i]);
    cutCell(roots_[items[i]],
            brickContext(cache, reach[i], fresh, tool_direction, counters[i], lazySolid));
  };
  runOnBricks(cache, items.size(), work);
  CutCounters step;
  for (const CutCounters& c : counters) step.add(c);  // fixed order: identical sums
  return step;
}

void Stock::checkInvariants() const {
  ensureSettled();
  for (const Cell& root : roots_) checkCell(root);
  const auto disagreements = sharedSampleDisagreements(*this, 1);
  if (!disagreements.empty())
    throw std::logic_error("mdh invariant: " + disagreements.front().describe());
}

}  // namespace mdhd::mdh

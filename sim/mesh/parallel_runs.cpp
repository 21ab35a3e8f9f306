#include "sim/mesh/parallel_runs.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <numeric>
#include <thread>
#include <utility>

namespace mdhd::mesh {

namespace {

void addStats(MeshStats& to, const MeshStats& s) {
  to.triangles += s.triangles;
  to.exteriorTriangles += s.exteriorTriangles;
  to.surfaceCubes += s.surfaceCubes;
  to.loops += s.loops;
  to.centreVertices += s.centreVertices;
  to.fallbackCrossings += s.fallbackCrossings;
  to.degenerateTriangles += s.degenerateTriangles;
  to.leaves += s.leaves;
}

// A buffered triangle without MeshVertex's padding: 104 bytes, not 128.
struct PackedTriangle {
  glm::dvec3 p[3];
  std::uint64_t where[3];
  VertexKind kind[3];
  bool exterior;
};
static_assert(sizeof(PackedTriangle) <= 104);

// The two ways a run's triangles go: into its slot, or straight to the sink.
// Both number the added vertices on from `base` (per run in a slot, over the
// whole mesh at the sink), as one mesher meshing the leaves in order would.
class PackedBuffer final : public MeshSink {
 public:
  void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                bool exterior) override {
    PackedTriangle t{{a.position, b.position, c.position}, {}, {}, exterior};
    const MeshVertex* v[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      t.kind[k] = v[k]->key.kind;
      t.where[k] = v[k]->key.where + (t.kind[k] == VertexKind::kInner ? base : 0);
    }
    tris.push_back(t);
  }
  std::vector<PackedTriangle> tris;
  std::uint64_t base = 0;
};

class Renumbered final : public MeshSink {
 public:
  Renumbered(MeshSink& to, std::uint64_t innerBase) : base(innerBase), to_(to) {}
  void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                bool exterior) override {
    MeshVertex v[3] = {a, b, c};
    for (MeshVertex& x : v)
      if (x.key.kind == VertexKind::kInner) x.key.where += base;
    to_.triangle(v[0], v[1], v[2], exterior);
  }
  std::uint64_t base;

 private:
  MeshSink& to_;
};

// Leaf by leaf, so that a run can be given up or switched between leaves; a
// fresh mesher per leaf numbers its added vertices from 0, `out.base` on.
template <class Out>
void meshLeaf(const MeshRun& run, const int& leaf, Out& out, MeshStats& stats) {
  MeshStats s;
  run(std::span<const int>(&leaf, 1), out, s);
  out.base += static_cast<std::uint64_t>(s.centreVertices);
  addStats(stats, s);
}

// One run's triangles between the thread that meshed it and the sink. Slot
// r % window serves run r; its vector keeps its capacity from run to run.
struct Slot {
  std::vector<PackedTriangle> tris;
  MeshStats stats;
  bool done = false;
};

}  // namespace

std::vector<std::size_t> cutRuns(std::span<const std::int64_t> work, std::int64_t maxWork,
                                 std::size_t minRuns) {
  const std::int64_t total = std::accumulate(work.begin(), work.end(), std::int64_t{0});
  const std::int64_t perRun = std::max<std::int64_t>(
      1, std::min(maxWork, total / static_cast<std::int64_t>(std::max<std::size_t>(1, minRuns))));
  std::vector<std::size_t> ends;
  std::int64_t sum = 0;
  for (std::size_t i = 0; i < work.size(); ++i) {
    sum += work[i];
    if (sum >= perRun) {
      ends.push_back(i + 1);
      sum = 0;
    }
  }
  if (!work.empty() && (ends.empty() || ends.back() != work.size())) ends.push_back(work.size());
  return ends;
}

void meshInParallel(std::span<const int> leaves, const ParallelRuns& runs, MeshSink& sink,
                    MeshStats& stats, const MeshRun& run) {
  const std::size_t count = runs.ends.size();
  const std::size_t window = static_cast<std::size_t>(std::max(1, runs.window));
  std::vector<Slot> slots(std::min(window, count));
  auto leavesOf = [&](std::size_t r) {
    const std::size_t first = r == 0 ? 0 : runs.ends[r - 1];
    return leaves.subspan(first, runs.ends[r] - first);
  };
  std::mutex mutex;
  std::condition_variable changed;  // workers wait on it for room in the window
  std::size_t next = 0;             // runs started
  std::size_t emitted = 0;          // runs handed to the sink
  std::exception_ptr error;
  std::atomic<std::size_t> emittedHint{0};  // `emitted`, read without the lock
  std::atomic<bool> failed{false};
  auto fail = [&](std::exception_ptr e) {
    std::lock_guard lock(mutex);
    if (!error) error = e;
    failed = true;
    changed.notify_all();
  };
  // Meshes run r into its slot; called with `mutex` held, returns with it held.
  // Gives up when the calling thread has sent the run to the sink itself.
  auto buffer = [&](std::unique_lock<std::mutex>& lock, std::size_t r) {
    PackedBuffer out;
    out.tris = std::move(slots[r % window].tris);  // run r - window has reached the sink
    lock.unlock();
    out.tris.clear();
    MeshStats s;
    std::exception_ptr e;
    try {
      for (const int& leaf : leavesOf(r)) {
        if (failed || emittedHint.load(std::memory_order_relaxed) > r) break;
        meshLeaf(run, leaf, out, s);
      }
    } catch (...) {
      e = std::current_exception();
    }
    lock.lock();
    if (e) {
      if (!error) error = e;
      failed = true;
      changed.notify_all();
    } else if (emitted <= r && !failed) {  // else the slot may be run r + window's by now
      Slot& slot = slots[r % window];
      slot.tris = std::move(out.tris);
      slot.stats = s;
      slot.done = true;
    }
  };
  auto worker = [&] {
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return error || next >= count || next < emitted + window; });
      if (error || next >= count) return;
      buffer(lock, next++);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < runs.threads; ++t) pool.emplace_back(worker);
  // The calling thread never waits: it sends a buffered run on, meshes the run
  // due straight into the sink, meshes a run ahead into its slot while the
  // window has room, and else meshes the due run (started by a worker that may
  // be descheduled on a busy machine) itself, switching to the worker's buffer
  // between leaves if that fills first.
  std::uint64_t innerBase = 0;  // kInner serials used by the runs before
  auto sendSlot = [&](const Slot& slot, std::int64_t skip) {
    for (std::size_t i = static_cast<std::size_t>(skip); i < slot.tris.size(); ++i) {
      const PackedTriangle& t = slot.tris[i];
      MeshVertex v[3];
      for (int k = 0; k < 3; ++k) {
        v[k].position = t.p[k];
        v[k].key = {t.where[k] + (t.kind[k] == VertexKind::kInner ? innerBase : 0), t.kind[k]};
      }
      sink.triangle(v[0], v[1], v[2], t.exterior);
    }
    innerBase += static_cast<std::uint64_t>(slot.stats.centreVertices);
    addStats(stats, slot.stats);
  };
  try {
    std::unique_lock lock(mutex);
    while (emitted < count && !error) {
      const std::size_t r = emitted;
      Slot& slot = slots[r % window];
      if (!slot.done && next != r && next < count && next < r + window) {
        buffer(lock, next++);
        continue;
      }
      const bool mine = next == r;  // else a worker has it
      if (mine) ++next;
      bool buffered = slot.done;
      slot.done = false;
      lock.unlock();
      // No worker touches the slot until `emitted` passes r.
      if (buffered) {
        sendSlot(slot, 0);
      } else {
        Renumbered out(sink, innerBase);
        MeshStats s;
        for (const int& leaf : leavesOf(r)) {
          if (!mine) {
            std::lock_guard check(mutex);
            buffered = std::exchange(slot.done, false);
          }
          if (buffered) break;
          meshLeaf(run, leaf, out, s);
        }
        if (buffered) {
          sendSlot(slot, s.triangles);  // its first triangles are the ones sent
        } else {
          innerBase = out.base;
          addStats(stats, s);
        }
      }
      lock.lock();
      // A worker that finished run r after the last look stored it in vain.
      slot.done = false;
      emitted = r + 1;
      emittedHint = emitted;
      changed.notify_all();
    }
  } catch (...) {
    fail(std::current_exception());
  }
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace mdhd::mesh

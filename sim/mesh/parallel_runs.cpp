#include "sim/mesh/parallel_runs.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <numeric>
#include <thread>

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

class PackedBuffer final : public MeshSink {
 public:
  void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                bool exterior) override {
    tris.push_back({{a.position, b.position, c.position},
                    {a.key.where, b.key.where, c.key.where},
                    {a.key.kind, b.key.kind, c.key.kind},
                    exterior});
  }
  std::vector<PackedTriangle> tris;
};

// Hands triangles on with the added vertices numbered after the runs before.
class Renumbered final : public MeshSink {
 public:
  Renumbered(MeshSink& to, std::uint64_t innerBase) : to_(to), base_(innerBase) {}
  void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                bool exterior) override {
    MeshVertex v[3] = {a, b, c};
    for (MeshVertex& x : v)
      if (x.key.kind == VertexKind::kInner) x.key.where += base_;
    to_.triangle(v[0], v[1], v[2], exterior);
  }

 private:
  MeshSink& to_;
  std::uint64_t base_;
};

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
  std::condition_variable changed;
  std::size_t next = 0;     // runs started
  std::size_t emitted = 0;  // runs handed to the sink
  std::exception_ptr error;
  auto fail = [&](std::exception_ptr e) {
    std::lock_guard lock(mutex);
    if (!error) error = e;
    changed.notify_all();
  };
  // Meshes run r into its slot; called with `mutex` held, returns with it held.
  auto buffer = [&](std::unique_lock<std::mutex>& lock, std::size_t r) {
    PackedBuffer out;
    out.tris = std::move(slots[r % window].tris);  // run r - window has reached the sink
    lock.unlock();
    out.tris.clear();
    MeshStats s;
    std::exception_ptr e;
    try {
      run(leavesOf(r), out, s);
    } catch (...) {
      e = std::current_exception();
    }
    lock.lock();
    if (e && !error) error = e;
    Slot& slot = slots[r % window];
    slot.tris = std::move(out.tris);
    slot.stats = s;
    slot.done = !e;
    changed.notify_all();
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
  // The calling thread meshes too: the run due at the sink straight into it when
  // no worker has started that run, else a run ahead into a slot, else it waits.
  std::uint64_t innerBase = 0;  // kInner serials used by the runs before
  try {
    std::unique_lock lock(mutex);
    while (emitted < count && !error) {
      const std::size_t r = emitted;
      Slot& slot = slots[r % window];
      if (next == r) {
        ++next;
        lock.unlock();
        Renumbered out(sink, innerBase);
        MeshStats s;
        run(leavesOf(r), out, s);
        innerBase += static_cast<std::uint64_t>(s.centreVertices);
        addStats(stats, s);
      } else if (slot.done) {
        slot.done = false;
        lock.unlock();
        // No one touches the slot until `emitted` passes r.
        for (const PackedTriangle& t : slot.tris) {
          MeshVertex v[3];
          for (int k = 0; k < 3; ++k) {
            v[k].position = t.p[k];
            v[k].key = {t.kind[k] == VertexKind::kInner ? t.where[k] + innerBase : t.where[k],
                        t.kind[k]};
          }
          sink.triangle(v[0], v[1], v[2], t.exterior);
        }
        innerBase += static_cast<std::uint64_t>(slot.stats.centreVertices);
        addStats(stats, slot.stats);
      } else if (next < count && next < emitted + window) {
        buffer(lock, next++);
        continue;
      } else {
        changed.wait(lock);
        continue;
      }
      lock.lock();
      emitted = r + 1;
      changed.notify_all();
    }
  } catch (...) {
    fail(std::current_exception());
  }
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace mdhd::mesh

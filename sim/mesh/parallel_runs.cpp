#include "sim/mesh/parallel_runs.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace mdhd::mesh {

namespace {

struct RunResult {
  std::vector<BufferedTriangle> tris;
  MeshStats stats;
  bool done = false;
};

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

}  // namespace

void meshInParallel(const std::vector<int>& leaves, int threads, MeshSink& sink, MeshStats& stats,
                    const MeshRun& run) {
  // Leaves differ a lot in cost: several runs per thread even the load out.
  const std::size_t perRun =
      std::max<std::size_t>(1, leaves.size() / (static_cast<std::size_t>(threads) * 8));
  const std::size_t runs = (leaves.size() + perRun - 1) / perRun;
  const std::size_t window = 4 * static_cast<std::size_t>(threads);
  std::vector<RunResult> results(runs);
  std::mutex mutex;
  std::condition_variable changed;
  std::size_t next = 0, emitted = 0;
  std::exception_ptr error;
  auto fail = [&](std::exception_ptr e) {
    std::lock_guard lock(mutex);
    if (!error) error = e;
    changed.notify_all();
  };
  auto worker = [&] {
    for (;;) {
      std::size_t i = 0;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return error || next >= runs || next < emitted + window; });
        if (error || next >= runs) return;
        i = next++;
      }
      TriangleBuffer buffer;
      MeshStats s;
      try {
        const std::size_t first = i * perRun;
        run(std::span<const int>(leaves.data() + first, std::min(perRun, leaves.size() - first)),
            buffer, s);
      } catch (...) {
        fail(std::current_exception());
        return;
      }
      std::lock_guard lock(mutex);
      results[i].tris = std::move(buffer.tris);
      results[i].stats = s;
      results[i].done = true;
      changed.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  std::uint64_t innerBase = 0;  // kInner serials used by the runs before
  try {
    for (std::size_t i = 0; i < runs; ++i) {
      RunResult r;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return error || results[i].done; });
        if (error) break;
        r = std::move(results[i]);
      }
      for (BufferedTriangle& t : r.tris) {
        for (MeshVertex& v : t.v)
          if (v.key.kind == VertexKind::kInner) v.key.where += innerBase;
        sink.triangle(t.v[0], t.v[1], t.v[2], t.exterior);
      }
      innerBase += static_cast<std::uint64_t>(r.stats.centreVertices);
      addStats(stats, r.stats);
      std::lock_guard lock(mutex);
      emitted = i + 1;
      changed.notify_all();
    }
  } catch (...) {
    fail(std::current_exception());
  }
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace mdhd::mesh

// Meshing on several threads gives the sink exactly what one thread gives:
// the same triangles in the same order, the same vertex keys (added vertices
// numbered on), the same statistics.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sim/mesh/parallel_runs.h"
#include "tests/mdh/random_tool_moves.h"
#include "tests/mesh/mesh_test_support.h"

namespace mdhd::mesh {
namespace {

void expectSame(const std::vector<BufferedTriangle>& a, const std::vector<BufferedTriangle>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].exterior, b[i].exterior) << i;
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(a[i].v[k].key, b[i].v[k].key) << i;
      ASSERT_EQ(a[i].v[k].position, b[i].v[k].position) << i;
    }
  }
}

void cut(mdh::Stock& stock, std::uint32_t seed) {
  mdh::testing::RandomToolMoves moves(seed, {{0, 0, 0}, {6, 6, 4}});
  for (int i = 0; i < 8; ++i) {
    const auto m = moves.next();
    stock.setToolRadius(0.4);
    stock.cut(m.sweep, m.direction);
  }
}

// Meshing on 2 and 3 threads with options `o` gives one thread's triangles, keys
// and statistics.
void expectSameOnTwoAndThreeThreads(const mdh::Stock& stock, MeshOptions o,
                                    const TriangleBuffer& one, const MeshStats& s1) {
  for (int threads : {2, 3}) {
    TriangleBuffer many;
    o.threads = threads;
    const MeshStats s = meshStock(stock, many, o);
    expectSame(one.tris, many.tris);
    EXPECT_EQ(s.triangles, s1.triangles);
    EXPECT_EQ(s.exteriorTriangles, s1.exteriorTriangles);
    EXPECT_EQ(s.loops, s1.loops);
    EXPECT_EQ(s.centreVertices, s1.centreVertices);
    EXPECT_EQ(s.surfaceCubes, s1.surfaceCubes);
    EXPECT_EQ(s.leaves, s1.leaves);
    EXPECT_EQ(s.fallbackCrossings, 0);
  }
}

TEST(ParallelMesh, SameTrianglesKeysAndStatsAsOneThread) {
  for (bool threeWay : {true, false}) {
    mdh::Stock stock({{0, 0, 0}, {6, 6, 4}}, testing::stockOptions(8, threeWay, 8));
    cut(stock, 3);
    TriangleBuffer one;
    MeshOptions o;
    const MeshStats s1 = meshStock(stock, one, o);
    EXPECT_GT(s1.leaves, 16);
    EXPECT_GT(s1.triangles, 10000);
    expectSameOnTwoAndThreeThreads(stock, o, one, s1);
  }
}

// Runs of one leaf each, at most two in flight: the same output again.
TEST(ParallelMesh, ManyTinyRunsAndANarrowWindow) {
  mdh::Stock stock({{0, 0, 0}, {6, 6, 4}}, testing::stockOptions(8, true, 8));
  cut(stock, 7);
  TriangleBuffer one;
  MeshOptions o;
  const MeshStats s1 = meshStock(stock, one, o);
  o.runWork = 1;
  o.runsPerThread = 1;
  expectSameOnTwoAndThreeThreads(stock, o, one, s1);
}

TEST(ParallelMesh, RunsCloseAtTheirWorkOrEarlierForBalance) {
  const std::vector<std::int64_t> work{3, 1, 1, 5, 2, 2, 2, 1};  // 17 in all
  EXPECT_EQ(cutRuns(work, 4, 1), (std::vector<std::size_t>{2, 4, 6, 8}));
  EXPECT_EQ(cutRuns(work, 100, 1), (std::vector<std::size_t>{8}));
  // At least 4 runs: at most 17 / 4 = 4 each, whatever maxWork says.
  EXPECT_EQ(cutRuns(work, 100, 4), (std::vector<std::size_t>{2, 4, 6, 8}));
  EXPECT_EQ(cutRuns(work, 1, 1), (std::vector<std::size_t>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_TRUE(cutRuns({}, 4, 2).empty());
}

// Each leaf gives two triangles naming it, each with an added vertex (numbered
// 0 and 1 by its mesher). The sink must get them in leaf order with the added
// vertices numbered on (2i, 2i + 1), and no leaf may be started while `window`
// runs before its run are still short of the sink. With slow workers (a busy
// machine) the calling thread meshes runs they hold itself.
TEST(ParallelMesh, WindowAndSlowWorkers) {
  std::vector<int> leaves(240);
  std::iota(leaves.begin(), leaves.end(), 0);
  ParallelRuns runs;
  for (std::size_t i = 3; i <= leaves.size(); i += 3) runs.ends.push_back(i);  // 3 leaves each
  const auto caller = std::this_thread::get_id();
  // Microseconds per leaf on the calling thread and on workers: both quick, slow
  // workers (the calling thread takes their runs over), both slow (workers also
  // finish runs the calling thread has begun to take over).
  for (const auto& [callerSlow, workerSlow] : {std::pair{20, 20}, {20, 1000}, {300, 300}}) {
    // Plain copies: a lambda may not capture a structured binding before C++20's
    // P1091 (clang 14).
    const int callerMicros = callerSlow, workerMicros = workerSlow;
    const bool slowWorkers = workerMicros > 10 * callerMicros;
    for (int threads : {1, 2, 3}) {
      for (int window : {1, 2, 5}) {
        runs.threads = threads;
        runs.window = window;
        std::atomic<int> furthest{-1}, calls{0};
        const MeshRun run = [&](std::span<const int> leaf, MeshSink& out, MeshStats& s) {
          ++calls;
          for (int i : leaf) {
            int f = furthest;
            while (i > f && !furthest.compare_exchange_weak(f, i)) {
            }
            // Every leaf takes a while, so that workers start runs at all.
            const bool onCaller = std::this_thread::get_id() == caller;
            std::this_thread::sleep_for(
                std::chrono::microseconds(onCaller ? callerMicros : workerMicros));
            MeshVertex a, b, c;
            a.key = {static_cast<std::uint64_t>(i), VertexKind::kCorner};
            for (std::uint64_t k : {0, 1}) {
              c.key = {k + static_cast<std::uint64_t>(s.centreVertices), VertexKind::kInner};
              out.triangle(a, b, c, false);
            }
            s.triangles += 2;
            s.centreVertices += 2;
          }
        };
        struct Check final : MeshSink {
          std::atomic<int>* furthest = nullptr;
          std::vector<std::uint64_t> leaf, inner;
          int worstAhead = 0;  // runs started beyond the one at the sink
          void triangle(const MeshVertex& a, const MeshVertex&, const MeshVertex& c,
                        bool) override {
            leaf.push_back(a.key.where);
            inner.push_back(c.key.where);
            worstAhead = std::max(worstAhead, *furthest / 3 - static_cast<int>(a.key.where / 3));
          }
        } sink;
        sink.furthest = &furthest;
        MeshStats stats;
        meshInParallel(leaves, runs, sink, stats, run);
        ASSERT_EQ(sink.leaf.size(), 2 * leaves.size());
        for (std::size_t i = 0; i < sink.leaf.size(); ++i) {
          ASSERT_EQ(sink.leaf[i], i / 2) << i;
          ASSERT_EQ(sink.inner[i], i) << i;
        }
        EXPECT_EQ(stats.triangles, 480);
        EXPECT_EQ(stats.centreVertices, 480);
        EXPECT_LE(sink.worstAhead, window - 1) << threads << " threads";
        // Slow workers: the calling thread re-meshed leaves a worker held (with a
        // window of 1 a worker rarely gets a run at all).
        if (slowWorkers && threads > 1 && window > 1) {
          EXPECT_GT(calls.load(), 240) << threads << " threads";
        }
      }
    }
  }
}

TEST(ParallelMesh, RegionToo) {
  mdh::Stock stock({{0, 0, 0}, {6, 6, 4}}, testing::stockOptions(8, true, 8));
  cut(stock, 5);
  MeshOptions o;
  o.region = geom::Aabb{{1, 1, 0}, {3.5, 4, 4}};
  TriangleBuffer one, two;
  meshStock(stock, one, o);
  o.threads = 2;
  meshStock(stock, two, o);
  EXPECT_GT(one.tris.size(), 100u);
  expectSame(one.tris, two.tris);
}

// A failing sink (a full disk under an STL writer) stops the workers and the
// error reaches the caller.
class FailingSink final : public MeshSink {
 public:
  void triangle(const MeshVertex&, const MeshVertex&, const MeshVertex&, bool) override {
    if (++count == 500) throw std::runtime_error("disk full");
  }
  int count = 0;
};

TEST(ParallelMesh, SinkErrorReachesTheCaller) {
  mdh::Stock stock({{0, 0, 0}, {6, 6, 4}}, testing::stockOptions(8, true, 8));
  cut(stock, 2);
  FailingSink sink;
  MeshOptions o;
  o.threads = 2;
  EXPECT_THROW(meshStock(stock, sink, o), std::runtime_error);
  EXPECT_EQ(sink.count, 500);
}

}  // namespace
}  // namespace mdhd::mesh

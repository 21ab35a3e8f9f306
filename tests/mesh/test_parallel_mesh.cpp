// Meshing on several threads gives the sink exactly what one thread gives:
// the same triangles in the same order, the same vertex keys (added vertices
// numbered on), the same statistics.
#include <atomic>
#include <numeric>
#include <stdexcept>
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

TEST(ParallelMesh, SameTrianglesKeysAndStatsAsOneThread) {
  for (bool threeWay : {true, false}) {
    mdh::Stock stock({{0, 0, 0}, {6, 6, 4}}, testing::stockOptions(8, threeWay, 8));
    cut(stock, 3);
    TriangleBuffer one;
    MeshOptions o;
    const MeshStats s1 = meshStock(stock, one, o);
    EXPECT_GT(s1.leaves, 16);
    EXPECT_GT(s1.triangles, 10000);
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
  for (int threads : {2, 3}) {
    TriangleBuffer many;
    o.threads = threads;
    const MeshStats s = meshStock(stock, many, o);
    expectSame(one.tris, many.tris);
    EXPECT_EQ(s.centreVertices, s1.centreVertices);
    EXPECT_EQ(s.leaves, s1.leaves);
  }
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

// Each run gives one triangle naming it (and an added vertex numbered from 0).
// The sink must get them in run order with the added vertices numbered on, and
// no run may start while `window` runs before it are still short of the sink.
TEST(ParallelMesh, WindowBoundsTheRunsInFlight) {
  std::vector<int> leaves(200);
  std::iota(leaves.begin(), leaves.end(), 0);
  ParallelRuns runs;
  for (std::size_t i = 1; i <= leaves.size(); ++i) runs.ends.push_back(i);
  for (int threads : {1, 2, 3}) {
    for (int window : {1, 2, 5}) {
      runs.threads = threads;
      runs.window = window;
      std::atomic<int> started{0};
      std::atomic<int> worstAhead{0};
      const MeshRun run = [&](std::span<const int> leaf, MeshSink& out, MeshStats& s) {
        ++started;
        MeshVertex a, b, c;
        a.key = {static_cast<std::uint64_t>(leaf[0]), VertexKind::kCorner};
        c.key = {0, VertexKind::kInner};
        out.triangle(a, b, c, false);
        ++s.triangles;
        ++s.centreVertices;
      };
      struct Check final : MeshSink {
        std::atomic<int>* started = nullptr;
        std::atomic<int>* worstAhead = nullptr;
        std::vector<std::uint64_t> runs, inner;
        void triangle(const MeshVertex& a, const MeshVertex&, const MeshVertex& c, bool) override {
          runs.push_back(a.key.where);
          inner.push_back(c.key.where);
          const int ahead = *started - static_cast<int>(a.key.where) - 1;
          if (ahead > *worstAhead) *worstAhead = ahead;
        }
      } sink;
      sink.started = &started;
      sink.worstAhead = &worstAhead;
      MeshStats stats;
      meshInParallel(leaves, runs, sink, stats, run);
      ASSERT_EQ(sink.runs.size(), leaves.size());
      for (std::size_t i = 0; i < leaves.size(); ++i) {
        EXPECT_EQ(sink.runs[i], i);
        EXPECT_EQ(sink.inner[i], i);
      }
      EXPECT_EQ(stats.triangles, 200);
      // Runs started beyond the one at the sink: at most window - 1.
      EXPECT_LE(worstAhead.load(), window - 1) << threads << " threads";
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

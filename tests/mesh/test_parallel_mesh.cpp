// Meshing on several threads gives the sink exactly what one thread gives:
// the same triangles in the same order, the same vertex keys (added vertices
// numbered on), the same statistics.
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

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

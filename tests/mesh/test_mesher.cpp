// The mesher on real stocks: closed, oriented, 2-manifold, and enclosing the
// engine's volume.
#include "sim/mesh/mesher.h"

#include <gtest/gtest.h>

#include "tests/mesh/mesh_test_support.h"

namespace mdhd::mesh {
namespace {

using testing::Ball;
using testing::Block;
using testing::expectWatertight;
using testing::meshOf;
using testing::stockOptions;

TEST(Mesher, UncutStockIsItsBox) {
  for (int brick : {0, 4, 32}) {
    mdh::Stock stock({{1, 2, 3}, {3, 3.5, 4}}, stockOptions(4, true, brick));
    const auto m = meshOf(stock);
    expectWatertight(m);
    // 8 x 6 x 4 cubes: every boundary square is two triangles.
    EXPECT_EQ(m.stats.triangles, 2 * 2 * (8 * 6 + 6 * 4 + 8 * 4));
    EXPECT_EQ(m.stats.exteriorTriangles, m.stats.triangles);
    EXPECT_NEAR(enclosedVolume(m.mesh), 2.0 * 1.5 * 1.0, 1e-12);
    EXPECT_NEAR(surfaceArea(m.mesh), 2 * (2 * 1.5 + 1.5 + 2), 1e-12);
  }
}

TEST(Mesher, SphereCutFromTheTop) {
  mdh::Stock stock({{0, 0, 0}, {10, 8, 6}}, stockOptions(10));
  stock.cut(Ball({5, 4, 6}, 2.0), {0, 0, 1});
  const auto m = meshOf(stock);
  expectWatertight(m);
  EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.01);
  EXPECT_EQ(m.stats.fallbackCrossings, 0);
}

}  // namespace
}  // namespace mdhd::mesh

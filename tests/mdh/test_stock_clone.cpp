// Stock::clone: a deep copy that answers every query as the original does and
// cuts on its own afterwards.
#include <gtest/gtest.h>

#include "sim/mdh/stock.h"
#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh {
namespace {

using testing::BoxSolid;
using testing::SphereSolid;

StockOptions options() {
  StockOptions o;
  o.brick = 16;
  o.threads = 1;
  o.density = 5;
  return o;
}

TEST(StockClone, CopiesEveryCellAndCutsIndependently) {
  Stock original({{0, 0, 0}, {10, 8, 6}}, options());
  original.cut(SphereSolid({5, 4, 6}, 2.5), {0, 0, 1});
  original.cut(BoxSolid({-1, 3, 2}, {4, 5, 3}), {1, 0, 0});  // a side slot: not +z
  const double before = original.volume();
  const Stats stats = original.stats();

  const std::unique_ptr<Stock> copy = original.clone();
  copy->checkInvariants();
  EXPECT_DOUBLE_EQ(copy->volume(), before);
  EXPECT_EQ(copy->stats().leaves, stats.leaves);
  EXPECT_EQ(copy->stats().directions, stats.directions);
  EXPECT_EQ(copy->steps(), original.steps());
  for (const glm::dvec3 p : {glm::dvec3(5, 4, 4.5), glm::dvec3(1, 4, 2.5), glm::dvec3(9, 7, 1)})
    EXPECT_EQ(copy->isSolid(p), original.isSolid(p)) << p.x << " " << p.y << " " << p.z;

  // Cutting the copy leaves the original as it was, and the other way round.
  const SphereSolid ball({2, 2, 6}, 1.5);
  const CutResult r = copy->cut(ball, {0, 0, 1});
  EXPECT_GT(r.removed_volume, 3.0);
  EXPECT_NEAR(copy->volume(), before - r.removed_volume, 1e-9);
  EXPECT_DOUBLE_EQ(original.volume(), before);
  EXPECT_TRUE(original.probe(ball, 0.01).touched);
  EXPECT_FALSE(copy->probe(ball, 0.01).touched);
  original.cut(BoxSolid({7, 5, 4}, {9, 7, 7}), {0, 0, 1});
  EXPECT_NEAR(copy->volume(), before - r.removed_volume, 1e-9);
  original.checkInvariants();
  copy->checkInvariants();
}

}  // namespace
}  // namespace mdhd::mdh

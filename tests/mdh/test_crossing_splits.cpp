// Planes along a line between its crossings, asked when the thesis's split
// types offer none, and what they do to the fallback splits on random cuts.
#include "sim/mdh/crossing_splits.h"

#include <gtest/gtest.h>

#include "sim/mdh/stock.h"
#include "tests/mdh/random_cuts.h"

namespace mdhd::mdh {
namespace {

// Two columns wide in x and y, seven vertices along z: no plane across the
// z lines exists, so only planes along z can separate anything.
const GridBox kThin{{0, 0, 0}, {1, 1, 6}};

void setLine(SampleGrid& g, int x, int y, bool (*solid)(int z)) {
  for (int z = 0; z <= 6; ++z) g.state(g.index(x, y, z)) = solid(z) ? SampleGrid::kSolid : 0;
}

TEST(CrossingSplits, BadLineIsCutBetweenItsCrossings) {
  SampleGrid g = SampleGrid::solid(kThin);
  setLine(g, 0, 0, [](int z) { return z < 2 || z > 3; });  // crossings on edges 1 and 3
  std::vector<SplitCandidate> out;
  crossingSplits(g, buildGoodBadMap(g, 2), kThin, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].axis, 2);
  EXPECT_EQ(out[0].lo, 2);
  EXPECT_EQ(out[0].hi, 3);
  EXPECT_EQ(out[0].type, SplitType::kDirect);
  out.clear();
  crossingSplits(g, buildGoodBadMap(g, 0), kThin, out);  // x lines: one sign only
  EXPECT_TRUE(out.empty());
}

TEST(CrossingSplits, NeighbouringOppositeSignsAreSeparatedAlongTheLines) {
  SampleGrid g(kThin);
  for (int y = 0; y <= 1; ++y) {
    setLine(g, 0, y, [](int z) { return z <= 1; });  // +z surface on edge 1
    setLine(g, 1, y, [](int z) { return z >= 4; });  // -z surface on edge 3
  }
  const GoodBadMap z = buildGoodBadMap(g, 2);
  ASSERT_TRUE(z.hasPositive && z.hasNegative && !z.hasBad);
  std::vector<SplitCandidate> out;
  crossingSplits(g, z, kThin, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].lo, 2);
  EXPECT_EQ(out[0].hi, 3);
  EXPECT_EQ(out[0].type, SplitType::kSignConflict);
}

TEST(CrossingSplits, OppositeSignsOnTheSameEdgeGiveNothing) {
  SampleGrid g(kThin);
  for (int y = 0; y <= 1; ++y) {
    setLine(g, 0, y, [](int z) { return z <= 2; });
    setLine(g, 1, y, [](int z) { return z >= 3; });
  }
  std::vector<SplitCandidate> out;
  crossingSplits(g, buildGoodBadMap(g, 2), kThin, out);
  EXPECT_TRUE(out.empty());
}

// The reference test's random 5-axis cuts (seeds 1-6, one root cell): before
// these planes were asked for, blind halvings were 148 of 1027 splits (14.4 %);
// with them 26 of 982 (31 of 1028 once forced vertices became cuts, VertexDrops).
TEST(CrossingSplits, FallbackHalvingsAreRareOnRandomCuts) {
  const geom::Aabb box{{0, 0, 0}, {6, 5, 4}};
  long long splits = 0, fallback = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    StockOptions o;
    o.density = 10;
    o.brick = 0;
    o.seed = seed;
    o.threads = 1;
    Stock stock(box, o);
    for (const auto& s : testing::randomCuts(seed, box, 4, 6)) {
      stock.setToolRadius(s.radius);
      stock.cut(*s.solid, s.direction);
    }
    stock.checkInvariants();
    splits += stock.stats().splits();
    fallback += stock.stats().splitsFallback;
  }
  std::printf("random cuts, seeds 1-6, brick 0: %lld splits, %lld fallback\n", splits, fallback);
  EXPECT_GT(splits, 500);
  EXPECT_LT(fallback * 100, 5 * splits);
}

}  // namespace
}  // namespace mdhd::mdh

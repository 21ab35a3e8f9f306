#include "sim/mdh/direct_splits.h"

#include <gtest/gtest.h>

namespace mdhd::mdh {
namespace {

DspSegment seg(int lo, int hi, bool unresolved = true) {
  return {lo, hi, unresolved, unresolved, true};
}

// Figure 3.18 in numbers: the tool segments fall into two overlap sets (A, B),
// A shrinks by a left-of-tool segment, B by a right-of-tool one, the last
// left segment forms its own set C, a resolved-resolved right segment (type
// 4) is dropped, and RelaxSets stretches B and C to touch the unresolved span.
TEST(DirectSplits, ComputeOverlapIntervalsFollowsTheFourSteps) {
  const auto sets = computeOverlapIntervals(
      seg(4, 9), {seg(4, 5), seg(1, 2)}, {seg(2, 6), seg(3, 7), seg(5, 9), seg(8, 12), seg(9, 11)},
      {seg(10, 14), seg(20, 22, false)});
  ASSERT_EQ(sets.size(), 3u);
  EXPECT_EQ(sets[0].lo, 5);  // A
  EXPECT_EQ(sets[0].hi, 5);
  EXPECT_EQ(sets[1].lo, 9);  // B: [10, 11] relaxed down to U's end
  EXPECT_EQ(sets[1].hi, 11);
  EXPECT_EQ(sets[2].lo, 1);  // C: [1, 2] relaxed up to U's start
  EXPECT_EQ(sets[2].hi, 4);
}

TEST(DirectSplits, OneOverlapSetIsASoleSeries) {
  const auto sets = computeOverlapIntervals(seg(3, 8), {}, {seg(2, 9), seg(4, 7), seg(3, 8)}, {});
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_EQ(sets[0].lo, 4);
  EXPECT_EQ(sets[0].hi, 7);
}

// A +z cell with a cave under its top: the z rays through the cave give one
// tool segment each, whose overlap holds the cave's height.
TEST(DirectSplits, CaveUnderTheTopGivesAZSplitThroughIt) {
  const GridBox box{{0, 0, 0}, {8, 8, 8}};
  SampleGrid g = SampleGrid::solid(box);
  for (int x = 3; x <= 5; ++x)
    for (int y = 0; y <= 8; ++y)
      for (int z = 3; z <= 5; ++z) g.state(g.index(x, y, z)) = SampleGrid::kWasSolid;
  markUnresolved(g, Direction{2, 1});
  const GoodBadMap z = buildGoodBadMap(g, 2);
  std::vector<SplitCandidate> out;
  directSplits(g, z, box, out);
  ASSERT_FALSE(out.empty());
  bool found = false;
  for (const auto& c : out)
    if (c.axis == 2 && c.lo <= 4 && c.hi >= 4) found = true;
  EXPECT_TRUE(found);
  for (const auto& c : out) EXPECT_EQ(c.type, SplitType::kDirect);
}

}  // namespace
}  // namespace mdhd::mdh

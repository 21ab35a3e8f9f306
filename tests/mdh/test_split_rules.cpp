#include "sim/mdh/split_rules.h"

#include <gtest/gtest.h>

namespace mdhd::mdh {
namespace {

const GridBox kCell{{0, 0, 0}, {40, 20, 20}};

SplitCandidate plane(int axis, int lo, int hi, SplitType type = SplitType::kIndirect,
                     bool complete = true, bool sole = false) {
  return {axis, lo, hi, type, complete, sole};
}

TEST(SplitRules, NamesRoundTrip) {
  for (Rule r : {Rule::kFFS, Rule::kFEFS, Rule::kFEFS_FFS, Rule::kCTD, Rule::kSPT, Rule::kRS})
    EXPECT_EQ(ruleFromName(ruleName(r)), r);
  EXPECT_FALSE(ruleFromName("FSF").has_value());
}

TEST(SplitRules, PlaneClosestToTheMiddle) {
  EXPECT_EQ(planeFor(plane(0, 5, 35), kCell), 20);
  EXPECT_EQ(planeFor(plane(0, 25, 35), kCell), 25);
  EXPECT_EQ(planeFor(plane(1, 2, 4), kCell), 4);
}

TEST(SplitRules, FurthestFromSidePrefersTheMostCentralPlane) {
  const std::vector<SplitCandidate> c{plane(0, 3, 3), plane(0, 32, 34), plane(2, 9, 9)};
  SelectionContext ctx{kCell};
  EXPECT_EQ(chooseSplit(c, {Rule::kFFS}, ctx), 2u);  // z = 9 lies 9 from a side, x = 32 only 8
}

TEST(SplitRules, ClosestToolcutDirectionPrefersPlanesContainingTheTool) {
  const std::vector<SplitCandidate> c{plane(2, 10, 10), plane(0, 20, 20)};
  SelectionContext ctx{kCell};
  ctx.toolDirection = {0, 0, 1};
  EXPECT_EQ(chooseSplit(c, {Rule::kCTD}, ctx), 1u);  // x = 20 contains the z tool axis
}

TEST(SplitRules, SplitPlaneTypeRanksCompleteThenSoleDirect) {
  const std::vector<SplitCandidate> c{plane(0, 20, 20, SplitType::kDirect, false, false),
                                      plane(0, 21, 21, SplitType::kDirect, false, true),
                                      plane(0, 22, 22, SplitType::kSignConflict, false),
                                      plane(0, 23, 23, SplitType::kSignConflict, true)};
  SelectionContext ctx{kCell};
  EXPECT_EQ(chooseSplit(c, {Rule::kSPT}, ctx), 3u);
  EXPECT_EQ(chooseSplit({c[0], c[1], c[2]}, {Rule::kSPT}, ctx), 1u);
}

TEST(SplitRules, FarEnoughFromSideThenFurthestFromSide) {
  // Tool radius 6: x = 5 is too close to a side, x = 12 and z = 10 are far enough.
  const std::vector<SplitCandidate> c{plane(0, 5, 5), plane(0, 12, 12), plane(2, 10, 10)};
  SelectionContext ctx{kCell};
  ctx.toolRadius = 6;
  ctx.toolDirection = {1, 0, 0};
  // FEFS keeps both far planes; CTD then prefers the one containing the x tool axis.
  EXPECT_EQ(chooseSplit(c, {Rule::kFEFS, Rule::kCTD}, ctx), 2u);
  // With every plane far enough FEFS-FFS falls back to FFS: x = 12 lies 12
  // from a side, z = 10 only 10.
  EXPECT_EQ(chooseSplit({c[1], c[2]}, {Rule::kFEFS_FFS}, ctx), 0u);
  // With a mixed set it acts as FEFS and keeps the tie for the next rule.
  EXPECT_EQ(chooseSplit(c, {Rule::kFEFS_FFS, Rule::kCTD}, ctx), 2u);
}

TEST(SplitRules, RandomSelectionDependsOnlyOnTheKey) {
  std::vector<SplitCandidate> c;
  for (int k = 1; k < 40; ++k) c.push_back(plane(0, k, k));
  SelectionContext ctx{kCell};
  std::vector<std::size_t> picks;
  for (std::uint64_t key = 0; key < 20; ++key) {
    ctx.randomKey = key;
    const std::size_t p = chooseSplit(c, {Rule::kRS}, ctx);
    EXPECT_EQ(chooseSplit(c, {Rule::kRS}, ctx), p);
    picks.push_back(p);
  }
  std::sort(picks.begin(), picks.end());
  EXPECT_GT(std::unique(picks.begin(), picks.end()) - picks.begin(), 5);
}

}  // namespace
}  // namespace mdhd::mdh

#include "sim/mdh/line_segments.h"

#include <cmath>

#include <gtest/gtest.h>

namespace mdhd::mdh {
namespace {

TEST(LineSegments, SubtractOpenKeepsToolBoundaryPoints) {
  const Span seg[] = {{0.0, 10.0}};
  const Span tool[] = {{2.0, 3.5}, {3.5, 4.0}, {9.0, 12.0}};
  std::vector<Span> out;
  subtractOpen(seg, tool, out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].lo, 0.0);
  EXPECT_EQ(out[0].hi, 2.0);
  EXPECT_EQ(out[1].lo, 3.5);  // the point where two open intervals meet survives
  EXPECT_EQ(out[1].hi, 3.5);
  EXPECT_EQ(out[2].lo, 4.0);
  EXPECT_EQ(out[2].hi, 9.0);
}

TEST(LineSegments, SubtractCoveringToolLeavesNothing) {
  const Span seg[] = {{1.0, 2.0}, {5.0, 6.0}};
  const Span tool[] = {{0.0, 7.0}};
  std::vector<Span> out;
  subtractOpen(seg, tool, out);
  EXPECT_TRUE(out.empty());
}

TEST(LineSegments, SegmentsFromSamples) {
  const std::vector<std::uint8_t> solid{1, 1, 1, 0, 0, 1, 1, 1};  // vertices 2..9
  std::vector<double> cross(7, std::nan(""));
  cross[2] = 4.25;  // edge 4-5
  cross[4] = 6.5;   // edge 6-7
  std::vector<Span> segs;
  segmentsFromSamples(2, solid, cross, segs);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].lo, 2.0);
  EXPECT_EQ(segs[0].hi, 4.25);
  EXPECT_EQ(segs[1].lo, 6.5);
  EXPECT_EQ(segs[1].hi, 9.0);
}

TEST(LineSegments, StrictlyInsideOpenIntervals) {
  const Span tool[] = {{2.0, 3.5}, {5.0, 6.0}};
  EXPECT_FALSE(strictlyInside(tool, 2.0));  // on the tool's surface: stays
  EXPECT_TRUE(strictlyInside(tool, 3.0));
  EXPECT_FALSE(strictlyInside(tool, 3.5));
  EXPECT_FALSE(strictlyInside(tool, 4.0));
  EXPECT_TRUE(strictlyInside(tool, 5.5));
  EXPECT_FALSE(strictlyInside(tool, 6.0));
  EXPECT_FALSE(strictlyInside({}, 1.0));
}

TEST(LineSegments, EdgeCrossingFollowsTheTool) {
  std::vector<Span> pieces;
  const Span tool[] = {{4.3, 9.0}};
  // A full edge cut from 4.3 on: the surface moves there.
  EXPECT_EQ(edgeCrossingAfterCut(true, true, std::nan(""), true, false, 4, tool, pieces), 4.3);
  // An old crossing the tool does not reach stays.
  EXPECT_EQ(edgeCrossingAfterCut(true, false, 4.2, true, false, 4, tool, pieces), 4.2);
  // Cut from the other side: the crossing is where the solid begins.
  const Span below[] = {{1.0, 4.6}};
  EXPECT_EQ(edgeCrossingAfterCut(true, true, std::nan(""), false, true, 4, below, pieces), 4.6);
}

TEST(LineSegments, EdgeCrossingLiesOnTheSolidSideOfTheEmptyEnd) {
  std::vector<Span> pieces;
  // The solid reaches the empty end exactly (a tool face on the grid plane):
  // kept just short of it, where a parent height of the same edge is.
  const Span tool[] = {{5.0, 9.0}};
  const double c = edgeCrossingAfterCut(true, true, std::nan(""), true, false, 4, tool, pieces);
  EXPECT_LT(c, 5.0);
  EXPECT_EQ(c, std::nextafter(5.0, 0.0));
  const Span below[] = {{0.0, 4.0}};
  const double d = edgeCrossingAfterCut(true, true, std::nan(""), false, true, 4, below, pieces);
  EXPECT_GT(d, 4.0);
  EXPECT_EQ(d, std::nextafter(4.0, 5.0));
}

TEST(LineSegments, EdgeCrossingAtTheSolidEndWhenTheLineDisagrees) {
  // The states come from the z lines (vertex_rule.h); where this line's tool
  // holds the solid end inside all the same (a tangency), the surface goes
  // through that end.
  std::vector<Span> pieces;
  const Span tool[] = {{3.5, 4.8}};
  EXPECT_EQ(edgeCrossingAfterCut(true, false, 4.6, true, false, 4, tool, pieces), 4.0);
  EXPECT_EQ(edgeCrossingAfterCut(false, true, 3.3, false, true, 3, tool, pieces), 4.0);
}

}  // namespace
}  // namespace mdhd::mdh

#include "sim/mdh/line_segments.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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
  const Span tool[] = {{4.3, 9.0}};
  // A full edge cut from 4.3 on: the surface moves there.
  EXPECT_EQ(edgeCrossingAfterCut(true, true, std::nan(""), true, false, 4, tool), 4.3);
  // An old crossing the tool does not reach stays.
  EXPECT_EQ(edgeCrossingAfterCut(true, false, 4.2, true, false, 4, tool), 4.2);
  // Cut from the other side: the crossing is where the solid begins.
  const Span below[] = {{1.0, 4.6}};
  EXPECT_EQ(edgeCrossingAfterCut(true, true, std::nan(""), false, true, 4, below), 4.6);
}

TEST(LineSegments, EdgeCrossingLiesOnTheSolidSideOfTheEmptyEnd) {
  // The solid reaches the empty end exactly (a tool face on the grid plane):
  // kept just short of it, where a parent height of the same edge is.
  const Span tool[] = {{5.0, 9.0}};
  const double c = edgeCrossingAfterCut(true, true, std::nan(""), true, false, 4, tool);
  EXPECT_LT(c, 5.0);
  EXPECT_EQ(c, std::nextafter(5.0, 0.0));
  const Span below[] = {{0.0, 4.0}};
  const double d = edgeCrossingAfterCut(true, true, std::nan(""), false, true, 4, below);
  EXPECT_GT(d, 4.0);
  EXPECT_EQ(d, std::nextafter(4.0, 5.0));
}

TEST(LineSegments, EdgeCrossingAtTheSolidEndWhenTheLineDisagrees) {
  // The states come from the z lines (vertex_rule.h); where this line's tool
  // holds the solid end inside all the same (a tangency), the surface goes
  // through that end.
  const Span tool[] = {{3.5, 4.8}};
  EXPECT_EQ(edgeCrossingAfterCut(true, false, 4.6, true, false, 4, tool), 4.0);
  EXPECT_EQ(edgeCrossingAfterCut(false, true, 3.3, false, true, 3, tool), 4.0);
}

// The answer as segment arithmetic spells it: the edge's solid before, minus the
// tool (subtractOpen), and the end of what is left next to the solid end.
double crossingBySegments(bool o0, bool o1, double oc, bool n0, bool n1, int k,
                          std::span<const Span> tool) {
  std::vector<Span> pieces;
  if (std::isnan(oc)) oc = k + 0.5;
  const Span before = o0 && o1 ? Span{double(k), double(k + 1)}
                      : o0     ? Span{double(k), oc}
                               : Span{oc, double(k + 1)};
  if (o0 || o1) subtractOpen(std::span<const Span>(&before, 1), tool, pieces);
  const double lo = n0 ? double(k) : std::nextafter(double(k), 1e300);
  const double hi = n0 ? std::nextafter(double(k + 1), -1e300) : double(k + 1);
  for (const Span& s : pieces) {
    if (n0 && !n1 && s.lo <= k) return std::clamp(s.hi, lo, hi);
    if (!n0 && n1 && s.hi >= k + 1) return std::clamp(s.lo, lo, hi);
  }
  return n0 ? lo : hi;
}

TEST(LineSegments, EdgeCrossingIsSegmentArithmetic) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int reached = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const int k = int(rng() % 5);
    // One to three tool intervals near the edge, some ends on its grid points.
    std::vector<double> ends;
    const int n = 1 + int(rng() % 3);
    for (int i = 0; i < 2 * n; ++i)
      ends.push_back(rng() % 4 == 0 ? double(k + int(rng() % 2)) : k - 0.5 + 2.0 * uni(rng));
    std::sort(ends.begin(), ends.end());
    std::vector<Span> tool;
    for (int i = 0; i + 1 < 2 * n; i += 2)
      if (ends[i] < ends[i + 1] && (tool.empty() || tool.back().hi < ends[i]))
        tool.push_back({ends[i], ends[i + 1]});
    const bool o0 = rng() % 2, o1 = rng() % 2;
    bool n0 = rng() % 2;
    const bool n1 = !n0;
    const double oc =
        o0 != o1 ? (rng() % 4 == 0 ? double(k + (o0 ? 0 : 1)) : k + uni(rng)) : std::nan("");
    const double want = crossingBySegments(o0, o1, oc, n0, n1, k, tool);
    const double got = edgeCrossingAfterCut(o0, o1, oc, n0, n1, k, tool);
    // Where the tool reaches the solid by more than kToolSlack the two agree to the
    // bit; within it the old crossing stays (by design).
    if (got != want) {
      ASSERT_TRUE(o0 == n0 && o1 == n1) << trial;
      ASSERT_NEAR(got, want, kToolSlack) << trial;
    } else {
      reached += !(o0 == n0 && o1 == n1);
    }
  }
  EXPECT_GT(reached, 50000);
}

}  // namespace
}  // namespace mdhd::mdh

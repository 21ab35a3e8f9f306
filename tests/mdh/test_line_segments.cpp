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

TEST(LineSegments, SamplesRoundTrip) {
  const Span segs[] = {{2.0, 4.25}, {6.5, 9.0}};
  std::vector<std::uint8_t> solid;
  std::vector<double> cross;
  samplesFromSegments(segs, 2, 8, solid, cross);  // vertices 2..9
  const std::vector<std::uint8_t> want{1, 1, 1, 0, 0, 1, 1, 1};
  EXPECT_EQ(solid, want);
  EXPECT_EQ(cross[2], 4.25);  // edge 4-5
  EXPECT_EQ(cross[4], 6.5);   // edge 6-7
  std::vector<Span> back;
  segmentsFromSamples(2, solid, cross, back);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].lo, 2.0);
  EXPECT_EQ(back[0].hi, 4.25);
  EXPECT_EQ(back[1].lo, 6.5);
  EXPECT_EQ(back[1].hi, 9.0);
}

TEST(LineSegments, SliverBetweenVerticesIsBelowResolution) {
  const Span segs[] = {{3.2, 3.7}};
  std::vector<std::uint8_t> solid;
  std::vector<double> cross;
  samplesFromSegments(segs, 0, 6, solid, cross);
  for (auto s : solid) EXPECT_EQ(s, 0);
}

}  // namespace
}  // namespace mdhd::mdh

// Moves that turn the tool axis: adaptive steps keep the sweep within the tolerance of
// a very fine stamping, fixed steps are exactly the union of their translations.
#include <thread>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/pose_interpolation.h"
#include "sim/geometry/signed_distance.h"
#include "sim/geometry/swept_volume.h"
#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::makeTool;

glm::dvec3 tilted(double degrees, const glm::dvec3& towards) {
  const double a = degrees * testing::kPi / 180.0;
  return glm::normalize(std::cos(a) * glm::dvec3(0, 0, 1) + std::sin(a) * glm::normalize(towards));
}

// Signed distance to the continuous motion: dense stamps, then a golden-section
// refinement between the neighbours of the best stamp.
struct Reference {
  const ToolPart& part;
  ToolPose a;
  ToolPose b;
  int stamps = 300;

  double sdAt(double f, const glm::dvec3& p) const {
    return signedDistance(part, interpolatePose(a, b, f), p);
  }
  double operator()(const glm::dvec3& p) const {
    int best = 0;
    double d = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= stamps; ++k) {
      const double dk = sdAt(double(k) / stamps, p);
      if (dk < d) d = dk, best = k;
    }
    const double lo = std::max(0, best - 1) / double(stamps);
    const double hi = std::min(stamps, best + 1) / double(stamps);
    return std::min(d,
                    testing::minimiseConvex([&](double s) { return sdAt(lo + s * (hi - lo), p); }));
  }
};

struct Agreement {
  int decided = 0;
  int wrong = 0;
};

// Samples the lines of a grid over the sweep's box; a sample farther than `band` from
// the reference surface must be inside an interval exactly when it is inside.
Agreement compare(const SweptVolume& s, const Reference& ref, double band) {
  Agreement r;
  const Aabb b = s.bounds();
  std::vector<Interval> out;
  for (int axis = 0; axis < 3; ++axis) {
    const int i1 = (axis + 1) % 3;
    const int i2 = (axis + 2) % 3;
    const double du = (b.hi[i1] - b.lo[i1]) / 6.0;
    const double dv = (b.hi[i2] - b.lo[i2]) / 6.0;
    for (double u = b.lo[i1] + du / 3; u < b.hi[i1]; u += du)
      for (double v = b.lo[i2] + dv / 3; v < b.hi[i2]; v += dv) {
        out.clear();
        s.lineIntervals(axis, u, v, out);
        for (double t = b.lo[axis]; t <= b.hi[axis]; t += 0.5) {
          glm::dvec3 p;
          p[axis] = t, p[i1] = u, p[i2] = v;
          const double d = ref(p);
          if (std::abs(d) <= band) continue;
          bool in = false;
          for (const Interval& iv : out) in = in || (t >= iv.lo && t <= iv.hi);
          ++r.decided;
          r.wrong += in != (d < 0);
        }
      }
  }
  return r;
}

TEST(FiveAxisSweep, AdaptiveStepsStayWithinTheTolerance) {
  const double tol = 0.01;
  for (ToolShape shape : {ToolShape::kBall, ToolShape::kFlat}) {
    const ToolPart part = makeToolPart(makeTool(shape), ToolPartKind::kCutter);
    const ToolPose a{{0, 0, 0}, {0, 0, 1}};
    const ToolPose b{{4, 2, -1}, tilted(30, {1, 0.5, 0})};
    const SweptVolume s = SweptVolume::between(part, a, b, 0, tol);
    EXPECT_LE(s.errorBound(), tol);
    EXPECT_GT(s.translations().size(), 10u);
    const Agreement r = compare(s, Reference{part, a, b}, tol + 1e-4);
    EXPECT_EQ(r.wrong, 0) << toolShapeName(shape);
    EXPECT_GT(r.decided, 1000);
    // The comparison can tell: one coarse step is off by more than the tolerance.
    const SweptVolume coarse = SweptVolume::between(part, a, b, 1, tol);
    EXPECT_GT(compare(coarse, Reference{part, a, b}, tol + 1e-4).wrong, 0);
  }
}

TEST(FiveAxisSweep, MidpointStepsKeepTheBoundWithOneTranslationFewer) {
  const double tol = 0.01;
  for (ToolShape shape : {ToolShape::kBall, ToolShape::kBull}) {
    const ToolPart part = makeToolPart(makeTool(shape), ToolPartKind::kCutter);
    const ToolPose a{{0, 0, 0}, {0, 0, 1}};
    const ToolPose b{{4, 2, -1}, tilted(30, {1, 0.5, 0})};
    const SweptVolume exact = SweptVolume::between(part, a, b, 0, tol);
    const SweptVolume mid = SweptVolume::between(part, a, b, 0, tol, SweepEnds::kMidpoints);
    EXPECT_EQ(mid.translations().size() + 1, exact.translations().size());
    EXPECT_EQ(mid.errorBound(), exact.errorBound());
    EXPECT_LE(mid.errorBound(), tol);
    const Agreement r = compare(mid, Reference{part, a, b}, tol + 1e-4);
    EXPECT_EQ(r.wrong, 0) << toolShapeName(shape);
    EXPECT_GT(r.decided, 1000);
    // The comparison can tell: one coarse midpoint step is off by more than the tolerance.
    const SweptVolume coarse = SweptVolume::between(part, a, b, 1, tol, SweepEnds::kMidpoints);
    EXPECT_EQ(coarse.translations().size(), 1u);
    EXPECT_GT(compare(coarse, Reference{part, a, b}, tol + 1e-4).wrong, 0);
  }
  // A 5-axis finishing move (the bench dome's: 15 degrees tilt, C turning 0.3 degrees,
  // 30 mm flutes): one translation instead of two for the same bound (about the
  // pivot of least turn rate, 16.7 mm up, the surface moves 13.7 mm a radian).
  Tool t = makeTool(ToolShape::kBall, 6.0, 30.0);
  t.length = 60.0;
  const ToolPart part = makeToolPart(t, ToolPartKind::kCutter);
  const double c = 0.3 * testing::kPi / 180.0;
  const ToolPose a{{0, 0, 0}, tilted(15, {1, 0, 0})};
  const ToolPose b{{0.5, 0, -0.05}, tilted(15, {std::cos(c), std::sin(c), 0})};
  EXPECT_EQ(SweptVolume::between(part, a, b, 0, 0.01).translations().size(), 2u);
  EXPECT_EQ(SweptVolume::between(part, a, b, 0, 0.01, SweepEnds::kMidpoints).translations().size(),
            1u);
}

TEST(FiveAxisSweep, TurningAboutTheTipAlone) {
  const double tol = 0.005;
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBull), ToolPartKind::kCutter);
  const ToolPose a{{1, 1, 1}, tilted(-20, {0, 1, 0})};
  const ToolPose b{{1, 1, 1}, tilted(25, {0.3, 1, 0})};
  const SweptVolume s = SweptVolume::between(part, a, b, 0, tol);
  EXPECT_LE(s.errorBound(), tol);
  const Agreement r = compare(s, Reference{part, a, b}, tol + 1e-4);
  EXPECT_EQ(r.wrong, 0);
  EXPECT_GT(r.decided, 1000);
}

TEST(FiveAxisSweep, SegmentCountFollowsTheTurnRateBound) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall), ToolPartKind::kCutter);
  // Ball r = 3 (centre 3 mm up), 12 mm of flutes: the pivot where the ball's centre and
  // the flutes' top rim move alike, p - 3 = hypot(3, 12 - p): p = 8, rate 5 (about the
  // centre height 6 the rim would move hypot(3, 6) = 6.7 a radian).
  const double pivot = part.turnPivot();
  EXPECT_NEAR(pivot, 8.0, 1e-6);
  EXPECT_NEAR(part.turnRate(8.0), 5.0, 1e-12);
  EXPECT_NEAR(part.turnRate(6.0), std::hypot(3.0, 6.0), 1e-12);
  const double rate = part.turnRate(pivot);
  const ToolPose a{{0, 0, 0}, {0, 0, 1}};
  const ToolPose b{{0, 0, 0}, tilted(30, {1, 0, 0})};
  const double th = testing::kPi / 6;
  for (double tol : {0.1, 0.01, 0.001}) {
    const int n = sweepSegments(part, a, b, 0, tol);
    // The turn alone needs n >= rate th / 2 tol; the sagitta a little more.
    const double turnOnly = std::ceil(rate * th / (2 * tol));
    EXPECT_GE(n, turnOnly) << tol;
    EXPECT_LE(n, 1.05 * turnOnly + 1) << tol;
    const double bound = rate * (th / n) / 2 + pivot * (th / n) * (th / n) / 4;
    EXPECT_LE(bound, tol) << tol;
    const SweptVolume s = SweptVolume::between(part, a, b, 0, tol);
    EXPECT_DOUBLE_EQ(s.errorBound(), bound);
    EXPECT_EQ(s.translations().size(), size_t(n) + 1);
  }
  EXPECT_EQ(sweepSegments(part, a, b, 7, 0.0), 7);
  EXPECT_EQ(sweepSegments(part, a, {{5, 0, 0}, {0, 0, 1}}, 0, 0.0), 1);  // a translation
}

TEST(FiveAxisSweep, PoseChainsKeepEveryPose) {
  // A chain that turns a corner: each pose's tip is in its translations.
  const ToolPart part = makeToolPart(makeTool(ToolShape::kFlat), ToolPartKind::kCutter);
  const ToolPose poses[] = {
      {{0, 0, 0}, {0, 0, 1}}, {{4, 0, 0}, {0, 0, 1}}, {{4, 3, 0}, tilted(5, {1, 0, 0})}};
  const SweptVolume s(part, poses);
  const auto& trs = s.translations();
  ASSERT_EQ(trs.size(), 3u);  // 0..4 merged; 4..(4,1.5) at pose 1; (4,1.5)..(4,3) at pose 2
  EXPECT_EQ(trs[0].to, glm::dvec3(4, 0, 0));
  EXPECT_EQ(trs[1].to, glm::dvec3(4, 1.5, 0));
  EXPECT_EQ(trs[2].from, glm::dvec3(4, 1.5, 0));
  EXPECT_EQ(trs[2].to, glm::dvec3(4, 3, 0));
  EXPECT_NEAR(s.errorBound(), 2 * part.reach() * std::sin(5 * testing::kPi / 180 / 4), 1e-15);
}

TEST(FiveAxisSweep, FixedStepsAreExactlyTheUnionOfTheirTranslations) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kDrill), ToolPartKind::kCutter);
  const ToolPose a{{0, 0, 0}, tilted(10, {0, 1, 0})};
  const ToolPose b{{6, 1, -2}, tilted(40, {1, 0, 0})};
  const SweptVolume s = SweptVolume::between(part, a, b, 4, 0.0);
  const auto& trs = s.translations();
  ASSERT_EQ(trs.size(), 5u);  // half, three whole, half
  EXPECT_EQ(trs.front().from, a.tip);
  EXPECT_EQ(trs.back().to, b.tip);
  EXPECT_EQ(trs.front().axis, a.axis);
  EXPECT_EQ(trs.back().axis, b.axis);
  std::vector<SweptVolume> parts;
  for (const Translation& tr : trs) {
    const ToolPose ends[2] = {{tr.from, tr.axis}, {tr.to, tr.axis}};
    parts.emplace_back(part, ends);
    ASSERT_EQ(parts.back().translations().size(), 1u);
    EXPECT_EQ(parts.back().translations()[0].to, tr.to);
  }
  const Aabb box = s.bounds();
  std::vector<Interval> got;
  std::vector<Interval> want;
  int lines = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const int i1 = (axis + 1) % 3;
    const int i2 = (axis + 2) % 3;
    for (double u = box.lo[i1]; u < box.hi[i1]; u += 0.37)
      for (double v = box.lo[i2]; v < box.hi[i2]; v += 0.37) {
        got.clear();
        want.clear();
        s.lineIntervals(axis, u, v, got);
        for (const SweptVolume& p : parts) p.lineIntervals(axis, u, v, want);
        // Union of the separate answers, merged the plain way.
        std::sort(want.begin(), want.end(), [](auto& x, auto& y) { return x.lo < y.lo; });
        std::vector<Interval> merged;
        for (const Interval& iv : want) {
          if (!merged.empty() && iv.lo <= merged.back().hi)
            merged.back().hi = std::max(merged.back().hi, iv.hi);
          else
            merged.push_back(iv);
        }
        ASSERT_EQ(got.size(), merged.size());
        for (size_t i = 0; i < got.size(); ++i) {
          EXPECT_EQ(got[i].lo, merged[i].lo);
          EXPECT_EQ(got[i].hi, merged[i].hi);
        }
        lines += !got.empty();
      }
  }
  EXPECT_GT(lines, 500);
}

TEST(FiveAxisSweep, ThreeAxisStepsMergeIntoOneExactTranslation) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kFlat), ToolPartKind::kCutter);
  const SweptVolume s =
      SweptVolume::between(part, {{0, 0, 0}, {0, 0, 1}}, {{3, 4, -1}, {0, 0, 1}}, 10, 0.01);
  ASSERT_EQ(s.translations().size(), 1u);
  EXPECT_EQ(s.translations()[0].to, glm::dvec3(3, 4, -1));
  EXPECT_EQ(s.errorBound(), 0.0);
}

TEST(FiveAxisSweep, BadArgumentsAreRefused) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBall), ToolPartKind::kCutter);
  const ToolPose up{{0, 0, 0}, {0, 0, 1}};
  const ToolPose tiltedPose{{0, 0, 0}, tilted(10, {1, 0, 0})};
  EXPECT_THROW(SweptVolume::between(part, up, {{0, 0, 0}, {0, 0, -1}}, 0, 0.01),
               std::invalid_argument);  // opposite axes
  EXPECT_THROW(SweptVolume::between(part, up, tiltedPose, 0, 0.0), std::invalid_argument);
  EXPECT_THROW(SweptVolume::between(part, up, tiltedPose, 0, -1.0), std::invalid_argument);
  EXPECT_THROW(SweptVolume::between(part, up, tiltedPose, 0, 1e-12), std::invalid_argument);
  EXPECT_THROW(SweptVolume::between(part, up, tiltedPose, -2, 0.01), std::invalid_argument);
  EXPECT_THROW(SweptVolume::between(part, up, {{0, 0, 0}, {0, 0, 0}}, 0, 0.01),
               std::invalid_argument);  // no axis
  EXPECT_THROW(SweptVolume::between(part, up, {{std::nan(""), 0, 0}, {0, 0, 1}}, 0, 0.01),
               std::invalid_argument);
  EXPECT_THROW(SweptVolume(part, std::span<const ToolPose>()), std::invalid_argument);
  // An axis that is not unit length is normalised, not refused.
  const SweptVolume s = SweptVolume::at(part, {{0, 0, 0}, {0, 0, 5}});
  std::vector<Interval> out;
  s.lineIntervals(2, 0.0, 0.0, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].hi, 12.0);
  out.clear();
  s.lineIntervals(3, 0.0, 0.0, out);  // no such axis: nothing
  EXPECT_TRUE(out.empty());
}

TEST(FiveAxisSweep, ConcurrentCallsGiveTheSameAnswers) {
  const ToolPart part = makeToolPart(makeTool(ToolShape::kBull), ToolPartKind::kCutter);
  const SweptVolume s = SweptVolume::between(part, {{0, 0, 0}, {0, 0, 1}},
                                             {{5, 0, 0}, tilted(20, {0, 1, 0})}, 0, 0.01);
  auto run = [&](std::vector<Interval>& all) {
    std::vector<Interval> out;
    for (double u = -5; u < 10; u += 0.25)
      for (double v = -2; v < 15; v += 0.25) {
        out.clear();
        s.lineIntervals(0, u, v, out);
        all.insert(all.end(), out.begin(), out.end());
      }
  };
  std::vector<Interval> one, two, alone;
  std::thread t1([&] { run(one); });
  std::thread t2([&] { run(two); });
  t1.join();
  t2.join();
  run(alone);
  ASSERT_EQ(one.size(), alone.size());
  ASSERT_EQ(two.size(), alone.size());
  EXPECT_GT(alone.size(), 100u);
  for (size_t i = 0; i < alone.size(); ++i) {
    EXPECT_EQ(one[i].lo, alone[i].lo);
    EXPECT_EQ(two[i].hi, alone[i].hi);
  }
}

}  // namespace
}  // namespace mdhd::geom

// Rows of lines asked at once (LineSolid::rowIntervals) against the same lines asked
// one by one: the answers must be the same to the bit, since the stock may take a
// line from either path (a row fill by one cell, a single line by another).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/axial_sweep.h"
#include "sim/geometry/cross_sweep.h"
#include "sim/geometry/static_solids.h"
#include "sim/geometry/swept_volume.h"
#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::makeTool;

std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

// Every line of the rows through `solid` along `axis`, at spacing h (and at the
// bounds' own coordinates, where boxes end), against lineIntervals; returns the
// number of lines that hit.
int compareRows(const LineSolid& solid, int axis, double h, std::mt19937& rng,
                const std::string& what) {
  const Aabb b = solid.bounds();
  const int i1 = (axis + 1) % 3, i2 = (axis + 2) % 3;
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<double> vs{b.lo[i2], b.hi[i2]};
  for (double v = std::floor(b.lo[i2] / h) * h - h; v <= b.hi[i2] + h; v += h) vs.push_back(v);
  int hits = 0;
  std::vector<Interval> row, one;
  for (const double v : vs) {
    std::vector<double> us;
    for (double u = std::floor(b.lo[i1] / h) * h - h; u <= b.hi[i1] + h; u += h)
      if (uni(rng) < 0.8) us.push_back(u);  // gaps, as a stock's row asks for some lines only
    us.push_back(b.lo[i1]);
    us.push_back(b.hi[i1]);
    std::sort(us.begin(), us.end());
    std::vector<std::size_t> ends(us.size());
    row.assign(3, Interval{-7.0, 7.0});  // what was there before stays
    solid.rowIntervals(axis, us, v, row, ends);
    std::size_t from = 3;
    for (std::size_t i = 0; i < us.size(); ++i) {
      one.clear();
      solid.lineIntervals(axis, us[i], v, one);
      const std::size_t got = ends[i] - from;
      EXPECT_EQ(got, one.size()) << what << " axis " << axis << " u " << us[i] << " v " << v;
      if (got != one.size()) return hits;
      for (std::size_t k = 0; k < got; ++k) {
        EXPECT_EQ(bits(row[from + k].lo), bits(one[k].lo))
            << what << " axis " << axis << " u " << us[i] << " v " << v << ": " << row[from + k].lo
            << " vs " << one[k].lo;
        EXPECT_EQ(bits(row[from + k].hi), bits(one[k].hi))
            << what << " axis " << axis << " u " << us[i] << " v " << v << ": " << row[from + k].hi
            << " vs " << one[k].hi;
      }
      hits += !one.empty();
      from = ends[i];
    }
    EXPECT_EQ(row.size(), from);
    EXPECT_EQ(row[0].lo, -7.0);
  }
  return hits;
}

// Lines along `axis` through `solid` in no order (a grid over its bounds at spacing h,
// some left out, some twice, shuffled) asked at once (linesIntervals) against
// lineIntervals; returns the number of lines that hit.
int compareLines(const LineSolid& solid, int axis, double h, std::mt19937& rng,
                 const std::string& what) {
  const Aabb b = solid.bounds();
  const int i1 = (axis + 1) % 3, i2 = (axis + 2) % 3;
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<std::pair<double, double>> lines{{b.lo[i1], b.lo[i2]}, {b.hi[i1], b.hi[i2]}};
  for (double v = std::floor(b.lo[i2] / h) * h - h; v <= b.hi[i2] + h; v += h)
    for (double u = std::floor(b.lo[i1] / h) * h - h; u <= b.hi[i1] + h; u += h) {
      const double r = uni(rng);
      if (r < 0.7) lines.push_back({u, v});
      if (r < 0.05) lines.push_back({u, v});
    }
  std::shuffle(lines.begin(), lines.end(), rng);
  std::vector<double> us, vs;
  for (const auto& [u, v] : lines) us.push_back(u), vs.push_back(v);
  std::vector<std::size_t> ends(us.size());
  std::vector<Interval> all(2, Interval{-7.0, 7.0}), one;  // what was there before stays
  solid.linesIntervals(axis, us, vs, all, ends);
  int hits = 0;
  std::size_t from = 2;
  for (std::size_t i = 0; i < us.size(); ++i) {
    one.clear();
    solid.lineIntervals(axis, us[i], vs[i], one);
    const std::size_t got = ends[i] - from;
    EXPECT_EQ(got, one.size()) << what << " axis " << axis << " u " << us[i] << " v " << vs[i];
    if (got != one.size()) return hits;
    for (std::size_t k = 0; k < got; ++k) {
      EXPECT_EQ(bits(all[from + k].lo), bits(one[k].lo))
          << what << " axis " << axis << " u " << us[i] << " v " << vs[i];
      EXPECT_EQ(bits(all[from + k].hi), bits(one[k].hi))
          << what << " axis " << axis << " u " << us[i] << " v " << vs[i];
    }
    hits += !one.empty();
    from = ends[i];
  }
  EXPECT_EQ(all.size(), from);
  EXPECT_EQ(all[0].lo, -7.0);
  return hits;
}

TEST(RowIntervals, ChainsOfEveryShapeAndPartMatchLineByLine) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const glm::dvec3 gridAxes[] = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0},
                                 {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}};
  int hits = 0, lineHits = 0, kernelHits = 0;
  for (ToolShape shape : testing::allShapes())
    for (ToolPartKind kind : {ToolPartKind::kCutter, ToolPartKind::kShank, ToolPartKind::kHolder}) {
      const ToolPart part = makeToolPart(makeTool(shape, 6.0, 12.0), kind);
      if (part.empty()) continue;
      for (int trial = 0; trial < 8; ++trial) {
        // A chain of short moves on one grid axis (a 3-axis batch), with a plunge, a
        // move square to the axis and a repeated pose (a stamp) among them.
        const glm::dvec3 w = gridAxes[trial % 6];
        std::vector<ToolPose> poses{{{uni(rng), uni(rng), uni(rng)}, w}};
        for (int j = 0; j < 6; ++j) {
          glm::dvec3 step(uni(rng), uni(rng), uni(rng));
          if (j == 1) step = 0.7 * uni(rng) * w;
          if (j == 2) step -= glm::dot(step, w) * w;
          if (j == 3) step = glm::dvec3(0.0);
          // Up by more than the part is long, then back over the same place: lines
          // along the axis meet the chain twice, apart.
          if (j == 4 && trial % 2 == 1) step = 40.0 * w;
          if (j == 5 && trial % 2 == 1) step = -(poses[4].tip - poses[1].tip) + 40.0 * w - step;
          poses.push_back({poses.back().tip + step, w});
        }
        const SweptVolume s = SweptVolume(part, poses);
        const std::string what = std::string(toolShapeName(shape)) + " part " +
                                 std::to_string(static_cast<int>(kind)) + " trial " +
                                 std::to_string(trial);
        for (int axis = 0; axis < 3; ++axis) {
          hits += compareRows(s, axis, 0.23, rng, what);
          const int h = compareLines(s, axis, 0.23, rng, what);
          lineHits += h;
          if (s.linesPay(axis)) kernelHits += h;  // square to the axis: crossExtentRow
        }
        if (HasFailure()) return;
      }
    }
  EXPECT_GT(hits, 20000);
  EXPECT_GT(lineHits, 20000);
  EXPECT_GT(kernelHits, 10000);
}

TEST(RowIntervals, TiltedTurningAndStandingToolsMatchLineByLine) {
  std::mt19937 rng(29);
  int hits = 0;
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape, 6.0, 12.0), ToolPartKind::kCutter);
    const ToolPose a{{0.3, -0.2, 0.1}, testing::randomUnit(rng)};
    const ToolPose b{{2.1, 0.9, -0.4}, testing::randomUnit(rng)};
    const SweptVolume turning = SweptVolume::between(part, a, b, 0, 0.05);
    const SweptVolume standing = SweptVolume::at(part, a);
    const SweptVolume upright = SweptVolume::at(part, {{0.05, 0.0, 0.0}, {0.0, 0.0, 1.0}});
    for (int axis = 0; axis < 3; ++axis) {
      hits +=
          compareLines(turning, axis, 0.31, rng, std::string(toolShapeName(shape)) + " turning");
      hits += compareLines(upright, axis, 0.1, rng, std::string(toolShapeName(shape)) + " upright");
      hits += compareRows(turning, axis, 0.31, rng, std::string(toolShapeName(shape)) + " turning");
      hits += compareRows(standing, axis, 0.19, rng, std::string(toolShapeName(shape)) + " at");
      hits += compareRows(upright, axis, 0.1, rng, std::string(toolShapeName(shape)) + " upright");
    }
    if (HasFailure()) return;
  }
  EXPECT_GT(hits, 5000);
}

TEST(RowIntervals, SolidsWithoutARowFormAnswerLineByLine) {
  std::mt19937 rng(3);
  const BoxSolid box({-1.0, -2.0, 0.5}, {1.5, 2.0, 3.0});
  const CylinderSolid cyl({0.0, 0.0, 0.0}, {0.2, 0.1, 1.0}, 1.5, 4.0);
  int hits = 0;
  for (int axis = 0; axis < 3; ++axis) {
    hits += compareRows(box, axis, 0.25, rng, "box");
    hits += compareRows(cyl, axis, 0.25, rng, "cylinder");
    hits += compareLines(box, axis, 0.25, rng, "box");
    hits += compareLines(cyl, axis, 0.25, rng, "cylinder");
  }
  EXPECT_GT(hits, 500);
}

// The row kernel on its own: every branch of axialExtent (a line missing the widest
// radius, grazing it within the tolerance, touching a move's end disk, plunges and
// stamps, moves with and against the axis) gives the same result and extent.
TEST(RowIntervals, AxialRowKernelMatchesAxialExtentToTheBit) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  long compared = 0, hits = 0;
  std::size_t mostRises = 0;
  for (ToolShape shape : testing::allShapes())
    for (ToolPartKind kind : {ToolPartKind::kCutter, ToolPartKind::kShank}) {
      // A coarse corner tolerance gives the bull a profile of a few rises (a kink
      // between each), which the kernel takes too.
      const ToolPart part = makeToolPart(makeTool(shape, 6.0, 12.0), kind, 0.2);
      for (const ConvexBody& body : part.bodies) {
        const std::optional<AxialProfile> p = axialProfile(body);
        if (!p || p->rises.size() > kRowRises) continue;
        mostRises = std::max(mostRises, p->rises.size());
        for (int trial = 0; trial < 60; ++trial) {
          glm::dvec3 d(uni(rng), uni(rng), uni(rng));
          if (trial % 5 == 0) d.x = d.y = 0.0;      // a plunge
          if (trial % 5 == 1) d.z = 0.0;            // square to the axis
          if (trial % 7 == 0) d = glm::dvec3(0.0);  // a stamp
          const double len = glm::length(d);
          const glm::dvec3 u = len > 0.0 ? d / len : glm::dvec3(0.0);
          const double sign = trial % 2 ? 1.0 : -1.0;
          const AxialMove m{u.x, u.y, u.x * u.x + u.y * u.y, sign * u.z, len};
          const double tol = 1e-12 * (p->maxRadius + len + 1.0);
          std::vector<double> q1;
          const double q2 = 1.5 * p->maxRadius * uni(rng);
          for (int i = 0; i < 200; ++i) q1.push_back(1.5 * (p->maxRadius + len) * uni(rng));
          // Lines at the widest radius from the trace (just in, on, just out) and at
          // its ends.
          const double across = std::hypot(u.x, u.y);
          for (const double off : {-2.0 * tol, -0.5 * tol, 0.0, 0.5 * tol, 2.0 * tol}) {
            const double r = p->maxRadius + off;
            if (across > 0.0) {
              const double nx = -u.y / across, ny = u.x / across;  // normal in the plane
              // u-offset putting the line at distance r from the trace, if q2 allows
              if (std::abs(nx) > 1e-3) q1.push_back((r - q2 * ny) / nx);
            }
            if (std::abs(q2) <= r) {
              q1.push_back(std::sqrt(r * r - q2 * q2));
              q1.push_back(len * u.x - std::sqrt(r * r - q2 * q2));
            }
          }
          const std::size_t n = q1.size();
          std::vector<double> lo(n), hi(n);
          std::vector<unsigned char> hit(n);
          axialExtentRow(*p, m, q1.data(), q2, n, tol, lo.data(), hi.data(), hit.data());
          for (std::size_t i = 0; i < n; ++i) {
            double l = 0.0, h = 0.0;
            const bool want = axialExtent(*p, m, q1[i], q2, tol, l, h);
            ASSERT_EQ(static_cast<bool>(hit[i]), want)
                << toolShapeName(shape) << " trial " << trial << " q1 " << q1[i] << " q2 " << q2;
            ++compared;
            if (!want) continue;
            ++hits;
            ASSERT_EQ(bits(lo[i]), bits(l)) << toolShapeName(shape) << " trial " << trial;
            ASSERT_EQ(bits(hi[i]), bits(h)) << toolShapeName(shape) << " trial " << trial;
          }
        }
      }
    }
  EXPECT_GE(mostRises, 2u);
  EXPECT_GT(compared, 20000);
  EXPECT_GT(hits, compared / 4);
}

}  // namespace
}  // namespace mdhd::geom

namespace mdhd::geom {
namespace {

// The cross kernel on its own, against crossExtent: every piece of every shape, moves
// along, across and square to the line, with and without a height change, levels
// through the piece's ends, and lines at one distance across the move (an edge's
// levels) or at many (a level's rows).
TEST(RowIntervals, CrossRowKernelMatchesCrossExtentToTheBit) {
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  long compared = 0, hits = 0;
  for (ToolShape shape : testing::allShapes()) {
    const ToolPart part = makeToolPart(makeTool(shape, 6.0, 12.0), ToolPartKind::kCutter, 0.2);
    for (const ConvexBody& body : part.bodies)
      for (const RevolvedPiece& rp : body.pieces) {
        const PieceQuadric p{rp.z0, rp.z1, rp.alpha, rp.beta, rp.gamma};
        for (int trial = 0; trial < 40; ++trial) {
          double zd = uni(rng), dn = uni(rng), de = uni(rng);
          if (trial % 4 == 0) de = 0.0;  // across the line (y lines of an x move)
          if (trial % 4 == 1) dn = 0.0;  // along the line
          if (trial % 3 == 0) zd = 0.0;  // level
          const double norm = std::sqrt(zd * zd + dn * dn + de * de);
          if (norm > 0.0) zd /= norm, dn /= norm, de /= norm;
          const double len = trial % 7 == 0 ? 0.0 : 2.0 * (1.0 + uni(rng));
          const CrossMove m{zd, dn, de, len, std::hypot(dn, de)};
          const double h0 = 4.0 * uni(rng);
          const double tol = 1e-12 * (6.0 + len + 1.0), qtol = 1e-13 * 49.0;
          std::vector<double> zeta;
          for (int i = 0; i < 120; ++i)
            zeta.push_back(p.z0 - 2.0 + (p.z1 - p.z0 + 4.0) * (i + 0.5) / 120.0);
          for (const double z : {p.z0, p.z1, p.z0 - 0.5 * tol, p.z1 + 0.5 * tol, p.z1 + 2.0 * tol,
                                 p.z0 + len * zd, p.z1 + len * zd})
            zeta.push_back(z);
          const std::size_t n = zeta.size();
          // Every other trial: the distance across varies line by line, through the
          // stadium's sides and the disks' edges.
          std::vector<double> h0s(n, h0);
          if (trial % 2 == 1)
            for (std::size_t i = 0; i < n; ++i) h0s[i] = h0 + 3.0 * uni(rng);
          std::vector<double> lo(n), hi(n);
          std::vector<unsigned char> hit(n);
          crossExtentRow(p, m, zeta.data(), h0s.data(), n, tol, qtol, lo.data(), hi.data(),
                         hit.data());
          for (std::size_t i = 0; i < n; ++i) {
            double l = 0.0, h = 0.0;
            const bool want = crossExtent(p, m, zeta[i], h0s[i], tol, qtol, l, h);
            ASSERT_EQ(static_cast<bool>(hit[i]), want)
                << toolShapeName(shape) << " trial " << trial << " zeta " << zeta[i];
            ++compared;
            if (!want) continue;
            ++hits;
            ASSERT_EQ(bits(lo[i]), bits(l)) << toolShapeName(shape) << " trial " << trial;
            ASSERT_EQ(bits(hi[i]), bits(h)) << toolShapeName(shape) << " trial " << trial;
          }
        }
      }
  }
  EXPECT_GT(compared, 20000);
  EXPECT_GT(hits, compared / 5);
}

}  // namespace
}  // namespace mdhd::geom

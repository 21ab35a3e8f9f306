// A cut looks only at the vertices near where its solid lies inside each brick and
// cell (cut_reach.h: LineSolid::boundsIn, much narrower than the solid's box for a
// leaning tool): the stock is the one a cut that looks at the whole box leaves, to the
// bit, for random 5-axis moves from every side (side maps, overhangs, splits) and a
// leaning raster; a bound that leaves part of the solid out leaves a different stock.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/geometry/swept_volume.h"
#include "sim/mdh/stock.h"
#include "tests/mdh/random_tool_moves.h"
#include "tests/mdh/stock_lines.h"
#include "tests/mdh/wavy_rows.h"

namespace mdhd::mdh {
namespace {

using testing::kWavyStock;

// The solid with boundsIn as LineSolid's default (its box clipped), or, `shrink` > 0,
// wrong on purpose: the true bound less `shrink` mm at its top.
class BoxBounds final : public geom::LineSolid {
 public:
  BoxBounds(const geom::SweptVolume& s, double shrink) : s_(s), shrink_(shrink) {}
  geom::Aabb bounds() const override { return s_.bounds(); }
  geom::Aabb boundsIn(const geom::Aabb& box) const override {
    if (shrink_ == 0.0) return LineSolid::boundsIn(box);
    geom::Aabb b = s_.boundsIn(box);
    b.hi.z -= shrink_;
    return b;
  }
  void lineIntervals(int axis, double u, double v,
                     std::vector<geom::Interval>& out) const override {
    s_.lineIntervals(axis, u, v, out);
  }
  void rowIntervals(int axis, std::span<const double> us, double v,
                    std::vector<geom::Interval>& out, std::span<std::size_t> ends) const override {
    s_.rowIntervals(axis, us, v, out, ends);
  }
  bool rowsPay(int axis) const override { return s_.rowsPay(axis); }
  void linesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                      std::vector<geom::Interval>& out,
                      std::span<std::size_t> ends) const override {
    s_.linesIntervals(axis, us, vs, out, ends);
  }
  bool linesPay(int axis) const override { return s_.linesPay(axis); }
  bool prismBand(int& axis, double& lo, double& hi) const override {
    return s_.prismBand(axis, lo, hi);
  }

 private:
  const geom::SweptVolume& s_;
  double shrink_;
};

// Random moves from every side, then a raster of a long ball leaning 25 degrees.
void cutAll(Stock& stock, double shrink, bool wrap) {
  testing::RandomToolMoves moves(11, kWavyStock);
  const auto cut = [&](const geom::SweptVolume& s, const glm::dvec3& dir) {
    if (wrap)
      stock.cut(BoxBounds(s, shrink), dir);
    else
      stock.cut(s, dir);
  };
  for (int i = 0; i < 12; ++i) {
    const testing::ToolMove m = moves.next();
    cut(m.sweep, m.direction);
  }
  const geom::ToolPart ball = testing::cutterPart(geom::ToolShape::kBall, 2.0);
  const double lean = 25.0 * std::acos(-1.0) / 180.0;
  const auto poses = testing::wavyRows(glm::dvec3(std::sin(lean), 0.0, std::cos(lean)), 30, 0.3);
  for (std::size_t i = 1; i < poses.size(); ++i)
    cut(geom::SweptVolume::between(ball, poses[i - 1], poses[i], 0, 0.01), poses[i].axis);
}

TEST(CutReach, ClippedToTheSolidLeavesTheStockOfTheSolidsBox) {
  Stock clipped(kWavyStock, testing::wavyOptions()), boxed(kWavyStock, testing::wavyOptions());
  cutAll(clipped, 0.0, false);
  cutAll(boxed, 0.0, true);
  EXPECT_LT(boxed.volume(), 0.95 * 12 * 12 * 8);
  EXPECT_EQ(clipped.volume(), boxed.volume());
  EXPECT_EQ(testing::differences(testing::allIntervals(clipped), testing::allIntervals(boxed)), 0);
  const Stats a = clipped.stats(), b = boxed.stats();
  EXPECT_EQ(a.leaves, b.leaves);
  EXPECT_EQ(a.directions, b.directions);
  EXPECT_EQ(a.overhangEvents, b.overhangEvents);
  EXPECT_GT(b.overhangEvents, 0);
  clipped.checkInvariants();
}

TEST(CutReach, ABoundThatMissesPartOfTheSolidLeavesADifferentStock) {
  Stock right(kWavyStock, testing::wavyOptions()), wrong(kWavyStock, testing::wavyOptions());
  cutAll(right, 0.0, false);
  cutAll(wrong, 0.5, true);
  EXPECT_GT(testing::differences(testing::allIntervals(wrong), testing::allIntervals(right)), 0);
}

}  // namespace
}  // namespace mdhd::mdh

// The downward-facing machined area: a hole drilled sideways into a block has the
// upper half of its wall facing down, pi r L, and the area is the same whatever
// the number of threads reading the grid lines.
#include "sim/check/overhang_area.h"

#include <numbers>

#include <gtest/gtest.h>

#include "sim/geometry/swept_volume.h"
#include "tests/mdh/random_tool_moves.h"

namespace mdhd::check {
namespace {

TEST(OverhangArea, SideHoleIsHalfItsWallAndThreadsChangeNothing) {
  for (int brick : {8, 32}) {
    mdh::StockOptions o;
    o.density = 10;
    o.brick = brick;
    o.threads = 1;
    mdh::Stock stock({{0, 0, 0}, {6, 6, 6}}, o);
    // A 2 mm flat end mill drilling 3 mm along -y into the y = 6 face, at z = 3.
    const double r = 1.0, depth = 3.0;
    const geom::ToolPart part = mdh::testing::cutterPart(geom::ToolShape::kFlat, 2 * r);
    const glm::dvec3 axis(0, 1, 0);
    stock.setToolRadius(r);
    stock.cut(
        geom::SweptVolume::between(part, {{3, 7, 3}, axis}, {{3, 6 - depth, 3}, axis}, 0, 0.001),
        axis);
    const double one = overhangArea(stock, 1);
    EXPECT_NEAR(one, std::numbers::pi * r * depth, 0.05 * std::numbers::pi * r * depth) << brick;
    EXPECT_EQ(overhangArea(stock, 2), one) << brick;
    EXPECT_EQ(overhangArea(stock, 3), one) << brick;
    EXPECT_EQ(overhangArea(stock, 64), one) << brick;  // more threads than rows of 16
  }
  // An uncut stock has no machined surface at all.
  mdh::Stock plain({{0, 0, 0}, {2, 2, 2}}, mdh::StockOptions{});
  EXPECT_EQ(overhangArea(plain, 2), 0.0);
}

}  // namespace
}  // namespace mdhd::check

// The example jobs of shared/examples whose cuts are simple enough to replay
// directly in the workpiece frame (the donut has its own test): the mesh is
// closed and encloses the stock minus the analytic removed volume the
// examples' README gives.
#include <gtest/gtest.h>

#include "tests/mesh/mesh_test_support.h"

namespace mdhd::mesh {
namespace {

using testing::expectWatertight;
using testing::meshOf;
using testing::stockOptions;

geom::ToolPart flatMill(double diameter) {
  geom::Tool t;
  t.number = 1;
  t.shape = geom::ToolShape::kFlat;
  t.diameter = diameter;
  t.flute_length = 20;
  t.length = 50;
  t.shank_diameter = diameter;
  return geom::makeToolPart(t, geom::ToolPartKind::kCutter);
}

// Area (mm^2) of the machined surfaces: triangles off the stock's box.
double machinedArea(const IndexedMesh& m) {
  double a = 0.0;
  for (std::size_t i = 0; i < m.triangles().size(); ++i) {
    if (m.exterior(i)) continue;
    const auto& t = m.triangles()[i];
    const auto& p = m.positions();
    a += 0.5 * glm::length(glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]));
  }
  return a;
}

TEST(ExampleJobs, Contour3AxisClearsTheRing) {
  // contour-3axis: a 6 mm flat end mill, tool centre on a 50 x 30 rectangle
  // with R5 corners, 2 mm deep, in a 100 x 80 x 40 stock (density 2 here).
  const double density = 2;
  mdh::Stock stock({{0, 0, -40}, {100, 80, 0}}, stockOptions(density));
  const geom::ToolPart part = flatMill(6);
  const glm::dvec3 up(0, 0, 1);
  stock.setToolRadius(3);
  std::vector<geom::ToolPose> path;
  auto line = [&](double x, double y) { path.push_back({{x, y, -2}, up}); };
  auto arc = [&](double cx, double cy, double from) {
    for (int k = 1; k <= 32; ++k) {
      const double a = from + k * (testing::kPi / 2) / 32;
      line(cx + 5 * std::cos(a), cy + 5 * std::sin(a));
    }
  };
  stock.cut(geom::SweptVolume::between(part, {{30, 25, 5}, up}, {{30, 25, -2}, up}, 0, 0.01), up);
  line(30, 25);
  line(70, 25);
  arc(70, 30, -testing::kPi / 2);
  line(75, 50);
  arc(70, 50, 0);
  line(30, 55);
  arc(30, 50, testing::kPi / 2);
  line(25, 30);
  arc(30, 30, testing::kPi);
  stock.cut(geom::SweptVolume(part, path), up);
  const auto m = meshOf(stock);
  expectWatertight(m);
  const double removed = 2 * (1961.1 - 1052.6);  // the README's figure
  const double h = 1 / density;
  const double area = machinedArea(m.mesh);
  EXPECT_NEAR(enclosedVolume(m.mesh), 100 * 80 * 40 - removed, 0.02 * area * h);
  EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.01 * area * h);
}

TEST(ExampleJobs, SideDrillHoleWithOverhang) {
  // side-drill-ac: an 8 mm flat end mill, axis (0, -1, 0) in W, drills from
  // the -y face to y = -5 (README), 15 mm deep; the hole's upper half overhangs.
  const double density = 4;
  mdh::Stock stock({{-20, -20, 0}, {20, 20, 30}}, stockOptions(density));
  const geom::ToolPart part = flatMill(8);
  const glm::dvec3 axis(0, -1, 0);
  stock.setToolRadius(4);
  stock.cut(geom::SweptVolume::between(part, {{0, -25, 15}, axis}, {{0, -5, 15}, axis}, 0, 0.01),
            axis);
  const auto m = meshOf(stock);
  expectWatertight(m);
  const double removed = testing::kPi * 16 * 15;  // 754.0
  const double h = 1 / density;
  const double area = machinedArea(m.mesh);
  EXPECT_NEAR(area, 2 * testing::kPi * 4 * 15 + testing::kPi * 16, 0.02 * area);
  EXPECT_NEAR(enclosedVolume(m.mesh), 40 * 40 * 30 - removed, 0.02 * area * h);
  // The engine's Coons-patch volume is the coarser of the two here (1.7 mm^3
  // off the analytic value, the mesh 0.4, at area x h = 106 mm^3): each within
  // its own discretisation error.
  EXPECT_NEAR(stock.volume(), 40 * 40 * 30 - removed, 0.02 * area * h);
  EXPECT_NEAR(enclosedVolume(m.mesh), stock.volume(), 0.03 * area * h);
  // The overhang: machined triangles facing down (the hole's upper half).
  double down = 0.0;
  for (std::size_t i = 0; i < m.mesh.triangles().size(); ++i) {
    if (m.mesh.exterior(i)) continue;
    const auto& t = m.mesh.triangles()[i];
    const auto& p = m.mesh.positions();
    const glm::dvec3 n = glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
    if (n.z < -0.01 * glm::length(n)) down += 0.5 * glm::length(n);
  }
  EXPECT_NEAR(down, testing::kPi * 4 * 15, 0.05 * testing::kPi * 4 * 15);  // about 188 mm^2
}

}  // namespace
}  // namespace mdhd::mesh

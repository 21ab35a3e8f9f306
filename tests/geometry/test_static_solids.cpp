// Fixture solids: axis-aligned boxes and cylinders at any angle.
#include "sim/geometry/static_solids.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

TEST(BoxSolid, LinesInsideGetTheBoxSpan) {
  const BoxSolid box({-10, -10, -20}, {110, 90, 0});
  std::vector<Interval> out;
  box.lineIntervals(2, 5.0, 5.0, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].lo, -20.0);
  EXPECT_EQ(out[0].hi, 0.0);
  box.lineIntervals(0, 90.0, -20.0, out);  // on the corner edge: closed box
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].lo, -10.0);
  EXPECT_EQ(out[1].hi, 110.0);
  out.clear();
  box.lineIntervals(1, 5.0, 0.1, out);    // above it
  box.lineIntervals(1, -25.0, 5.0, out);  // below it
  EXPECT_TRUE(out.empty());
  EXPECT_NEAR(testing::integrateVolume(box, 1, 1.0), 120.0 * 100 * 20, 1e-6);
  EXPECT_EQ(box.bounds().hi, glm::dvec3(110, 90, 0));
}

TEST(BoxSolid, RefusesInsideOutBoxes) {
  EXPECT_THROW(BoxSolid({0, 0, 1}, {1, 1, 0}), std::invalid_argument);
  EXPECT_THROW(BoxSolid({0, 0, 0}, {1, std::nan(""), 1}), std::invalid_argument);
}

TEST(CylinderSolid, UprightCylinderIsExact) {
  const CylinderSolid c({1, 2, 3}, {0, 0, 1}, 4.0, 10.0);
  std::vector<Interval> out;
  c.lineIntervals(2, 1.0 + 4.0 * std::cos(0.3), 2.0 + 4.0 * std::sin(0.3) - 1e-9, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].lo, 3.0, 1e-12);
  EXPECT_NEAR(out[0].hi, 13.0, 1e-12);
  out.clear();
  c.lineIntervals(0, 2.0 + 2.0, 5.0, out);  // y = 4 at z 5: x = 1 +- sqrt(16 - 4)
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].lo, 1.0 - std::sqrt(12.0), 1e-12);
  EXPECT_NEAR(out[0].hi, 1.0 + std::sqrt(12.0), 1e-12);
}

TEST(CylinderSolid, AnyAxisKeepsItsVolume) {
  const double exact = testing::kPi * 9.0 * 7.0;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(1, -2, 0.5));
  const CylinderSolid c({0.5, 0, -1}, 3.0 * axis, 3.0, 7.0);  // axis length does not matter
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(testing::integrateVolume(c, a, 0.05), exact, 2e-4 * exact);
  // Ends: along the axis through the centre, from base to base + height * axis.
  std::vector<Interval> out;
  const CylinderSolid lying({0, 0, 0}, {1, 0, 0}, 2.0, 5.0);
  lying.lineIntervals(0, 0.0, 0.0, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].lo, 0.0);
  EXPECT_EQ(out[0].hi, 5.0);
}

TEST(CylinderSolid, RefusesDegenerateSizes) {
  EXPECT_THROW(CylinderSolid({0, 0, 0}, {0, 0, 1}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(CylinderSolid({0, 0, 0}, {0, 0, 1}, 1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(CylinderSolid({0, 0, 0}, {0, 0, 0}, 1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace mdhd::geom

// Tool checks and derived sizes.
#include "sim/geometry/tool.h"

#include <gtest/gtest.h>

#include "tests/geometry/geometry_test_support.h"

namespace mdhd::geom {
namespace {

using testing::makeTool;

TEST(Tool, ShapeNamesRoundTrip) {
  for (ToolShape s : testing::allShapes()) EXPECT_EQ(toolShapeFromName(toolShapeName(s)), s);
  EXPECT_FALSE(toolShapeFromName("Ball").has_value());
  EXPECT_FALSE(toolShapeFromName("").has_value());
}

TEST(Tool, DerivedHeights) {
  Tool t = makeTool(ToolShape::kDrill);
  t.tip_angle = 90.0;
  EXPECT_NEAR(t.tipHeight(), 3.0, 1e-12);
  EXPECT_EQ(t.holderBottom(), 25.0);  // 50 - 15 - 10
  EXPECT_EQ(makeTool(ToolShape::kBall).tipHeight(), 3.0);
  EXPECT_EQ(makeTool(ToolShape::kBull).tipHeight(), 1.0);
  EXPECT_EQ(makeTool(ToolShape::kFlat).tipHeight(), 0.0);
}

TEST(Tool, ValidToolsPass) {
  for (ToolShape s : testing::allShapes())
    EXPECT_FALSE(validateTool(makeTool(s))) << toolShapeName(s);
  Tool ballLikeBull = makeTool(ToolShape::kBull);
  ballLikeBull.corner_radius = 3.0;  // = R is allowed
  EXPECT_FALSE(validateTool(ballLikeBull));
  Tool exact = makeTool(ToolShape::kFlat);
  exact.flute_length = 25.0;  // flutes right up to the holder
  EXPECT_FALSE(validateTool(exact));
}

TEST(Tool, ProblemsNameTheField) {
  struct Case {
    ToolShape shape;
    void (*edit)(Tool&);
    const char* field;
  };
  const Case cases[] = {
      {ToolShape::kFlat, [](Tool& t) { t.number = 0; }, "number"},
      {ToolShape::kFlat, [](Tool& t) { t.diameter = std::nan(""); }, "diameter"},
      {ToolShape::kFlat, [](Tool& t) { t.length = -1; }, "length"},
      {ToolShape::kFlat, [](Tool& t) { t.holder[1].diameter = 0; }, "holder[1].diameter"},
      {ToolShape::kBall, [](Tool& t) { t.flute_length = 2.9; }, "flute_length"},
      {ToolShape::kBull, [](Tool& t) { t.corner_radius = 3.01; }, "corner_radius"},
      {ToolShape::kDrill, [](Tool& t) { t.tip_angle = 180; }, "tip_angle"},
      {ToolShape::kFlat, [](Tool& t) { t.holder[0].length = 40; }, "holder"},
      {ToolShape::kFlat, [](Tool& t) { t.flute_length = 51; }, "flute_length"},
  };
  for (const Case& c : cases) {
    Tool t = makeTool(c.shape);
    c.edit(t);
    const auto p = validateTool(t);
    ASSERT_TRUE(p.has_value()) << c.field;
    EXPECT_EQ(p->field, c.field);
    EXPECT_FALSE(p->message.empty());
  }
}

}  // namespace
}  // namespace mdhd::geom

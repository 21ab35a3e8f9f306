// Per-tool statistics: each tool's removed volume (from the stock's volume at tool
// changes) and cutting time.
#include <gtest/gtest.h>

#include "tests/check/check_fixture.h"

namespace mdhd::check {
namespace {

const ToolUse* useOf(const Report& r, int tool) {
  for (const ToolUse& u : r.stats.tools)
    if (u.tool == tool) return &u;
  return nullptr;
}

TEST(ToolUse, EachToolIsCreditedWithWhatItRemoved) {
  rig::Rig s;
  geom::Tool small = rig::flatTool(2);
  small.diameter = small.shank_diameter = 4;
  s.tools = {rig::flatTool(1), small, rig::flatTool(3)};
  const Report r =
      rig::run(std::move(s),
               "T1 M6\nG43 H1\nS1000 M3\n"
               "G0 X5 Y10 Z5\nG1 Z-2 F500\nG1 X35\nG0 Z5\n"            // 6 mm slot, 2 deep
               "T3 M6\nG43 H3\nG0 X5 Y10 Z5\nG1 Z-1\n"  // in the air of the slot,
               "G1 X15\nG1 X25\nG1 X30\nG0 Z5\n"             // along it (a batch of moves)
               "T2 M6\nG43 H2\nG0 X5 Y30 Z5\nG1 Z-3\nG1 X35\nG0 Z5\n"  // 4 mm, 3 deep
               "M30\n");
  const double first = 2 * (pi * 9 + 30 * 6), second = 3 * (pi * 4 + 30 * 4);
  const ToolUse* t1 = useOf(r, 1);
  const ToolUse* t2 = useOf(r, 2);
  ASSERT_NE(t1, nullptr);
  ASSERT_NE(t2, nullptr);
  EXPECT_NEAR(t1->removed_volume_mm3, first, 0.02 * first);
  EXPECT_NEAR(t2->removed_volume_mm3, second, 0.02 * second);
  EXPECT_GT(t1->cutting_time_s, 0.0);
  EXPECT_GT(t2->cutting_time_s, 0.0);
  // Tool 3 only went down into the empty slot and along it (a batch of steps that
  // reaches the cut maps): it cut nothing.
  EXPECT_EQ(useOf(r, 3), nullptr);
  EXPECT_NEAR(t1->removed_volume_mm3 + t2->removed_volume_mm3, r.stats.removed_volume_mm3, 1e-6);
}

// Cutting time counts the feed moves that removed material, each whole: air moves
// before, a retract up its own slot and a move above the stock after do not count,
// whether the steps are cut one by one or batched (they form one chain here).
TEST(ToolUse, CuttingTimeCountsOnlyMovesThatRemoveMaterial) {
  for (const int batch : {1, 16}) {
    rig::Rig s;
    s.options.batch_steps = batch;
    const Report r = rig::run(std::move(s),
                              "T1 M6\nG43 H1\nS1000 M3\n"
                              "G0 X-10 Y10 Z5\n"
                              "G1 Z2 F600\n"  // air: 0.3 s
                              "G1 X5\n"       // air, 2 mm above the top: 1.5 s
                              "G1 Z-1\n"      // plunge: 0.3 s
                              "G1 X25\n"      // slot: 2 s
                              "G1 Z2\n"       // up its own slot: 0.3 s
                              "G1 X35\n"      // above the stock: 1 s
                              "M30\n");
    const ToolUse* t1 = useOf(r, 1);
    ASSERT_NE(t1, nullptr) << batch;
    EXPECT_NEAR(t1->cutting_time_s, 0.3 + 2.0, 1e-9) << batch;
    EXPECT_NEAR(t1->removed_volume_mm3, 1 * (pi * 9 + 20 * 6), 0.02 * (pi * 9 + 20 * 6)) << batch;
  }
}

}  // namespace
}  // namespace mdhd::check

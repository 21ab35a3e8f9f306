// Each collision type of the spec (section 5) on 3-axis and 5-axis machines: the
// episode, its first line, the place of first contact and the depth.
#include <cmath>
#include <numbers>
#include <tuple>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sim/geometry/static_solids.h"
#include "tests/check/check_fixture.h"

namespace mdhd::check {
namespace {

using rig::flatTool;
using rig::ofType;
using rig::Rig;
using rig::run;

using std::numbers::pi;
constexpr const char* kStart = "G21 G90 G17\nT1 M6\nG43 H1\n";  // lines 1-3

TEST(Collisions, RapidIntoStockRemovesAndIsOneEpisode) {
  Rig s;
  s.options.density = 5;
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S9000\n"       // 4
                                         "G0 X20 Y20 Z5\n"  // 5
                                         "G0 Z-2\n"         // 6: 2 mm into the stock
                                         "G0 X24\n"         // 7: and on sideways
                                         "G0 Z5\nM5\nM30\n");
  ASSERT_EQ(r.collisions.size(), 1u);
  const Collision& c = r.collisions[0];
  EXPECT_EQ(c.type, CollisionType::kRapidIntoStock);
  EXPECT_EQ(c.line, 6);
  EXPECT_EQ(c.last_line, 7);
  EXPECT_EQ(c.block, "G0 Z-2");
  EXPECT_EQ(c.tool, 1);
  EXPECT_NEAR(c.position.z, 0.0, 0.15);  // first contact at the stock top
  EXPECT_NEAR(c.position.x, 20.0, 1e-9);
  EXPECT_NEAR(c.joints[gcode::kZ], c.position.z + 40.0, 1e-6);  // G43: Z joint = tip + length
  EXPECT_NEAR(c.depth, 2.0, 0.2);
  // The removal happened: a 6 mm hole 2 mm deep, then a 4 mm long slot of it.
  const double removed = 2 * (pi * 9 + 4 * 6);
  EXPECT_NEAR(r.stats.removed_volume_mm3, removed, 0.03 * removed);
  EXPECT_EQ(r.status, Status::kCollisions);
}

TEST(Collisions, CutWithTheSpindleOff) {
  Rig s;
  s.options.density = 5;
  const Report r = run(std::move(s), std::string(kStart) +
                                         "G0 X20 Y20 Z5\n"  // 4 (never started: M3 missing)
                                         "G1 Z-2 F200\n"    // 5
                                         "G1 X30\n"         // 6
                                         "G0 Z5\n"          // 7
                                         "M3 S9000\n"       // 8
                                         "G1 X10 Z-1\n"     // 9 spindle on: a clean cut
                                         "M5\n"             // 10
                                         "G1 Y30\n"         // 11 stopped again
                                         "M30\n");
  const auto off = ofType(r, CollisionType::kSpindleOffCut);
  ASSERT_EQ(off.size(), 2u);
  EXPECT_EQ(off[0]->line, 5);
  EXPECT_EQ(off[0]->last_line, 6);
  EXPECT_NEAR(off[0]->depth, 2.0, 0.2);
  EXPECT_EQ(off[1]->line, 11);
  EXPECT_EQ(r.collisions.size(), 2u);
  EXPECT_GT(r.stats.removed_volume_mm3, 0.0);
}

// M3 or M4 at S0 turns nothing: a cut then is a cut with the spindle off. Until session
// 23 only M5 (or no M3) counted, and both cuts below ran `clean`.
TEST(Collisions, CutWithTheSpindleOnAtZeroSpeed) {
  Rig s;
  s.options.density = 5;
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S0\n"          // 4: on, at 0 rpm
                                         "G0 X20 Y20 Z5\n"  // 5
                                         "G1 Z-2 F200\n"    // 6: into the stock, standing still
                                         "S9000\n"          // 7
                                         "G1 X30\n"         // 8: turning: a clean cut
                                         "S0\n"             // 9
                                         "G1 Y30\n"         // 10: standing still again
                                         "G0 Z5\nM30\n");
  const auto off = ofType(r, CollisionType::kSpindleOffCut);
  ASSERT_EQ(off.size(), 2u);
  EXPECT_EQ(off[0]->line, 6);
  EXPECT_EQ(off[0]->last_line, 6);
  EXPECT_NEAR(off[0]->depth, 2.0, 0.2);
  EXPECT_EQ(off[1]->line, 10);
  EXPECT_NEAR(off[1]->position.y, 20.0, 0.15);  // at once: the cutter starts in the slot's end
  EXPECT_EQ(r.collisions.size(), 2u);
  // The removal happens all the same, 2 mm deep: the hole and a 10 mm slot along x (a
  // disc and 10 x 6 mm), then 10 mm along y from the slot's end (10 x 6 mm and a half
  // disc, less the 3 x 3 mm and the quarter disc the first slot had taken).
  const double removed = 2 * (pi * 9 + 60 + 60 + pi * 9 / 2 - 9 - pi * 9 / 4);
  EXPECT_NEAR(r.stats.removed_volume_mm3, removed, 0.02 * removed);
}

// A tool change ends the contacts of the tool before it: the next tool's contact is
// its own episode with its own tool, line and depth, even when the two touch in
// consecutive moves (M6 moves nothing). Until session 23 the key of an episode did not
// hold the tool: tool 2's rapid at line 10 (1 mm deeper into tool 1's hole) and its
// holder dragged at line 10 were reported as tool 1's episodes from line 6 to 10.
TEST(Collisions, AToolChangeEndsTheEpisodesOfTheToolBefore) {
  const auto twoTools = [] {
    Rig s;
    s.options.density = 5;
    s.tools = {flatTool(1), flatTool(2)};
    return s;
  };
  const std::string change =
      "T2 M6\n"      // 7
      "G43 H2\n"     // 8
      "M3 S9000\n";  // 9
  {
    const Report r = run(twoTools(), std::string(kStart) +
                                         "M3 S9000\n"       // 4
                                         "G0 X20 Y20 Z5\n"  // 5
                                         "G0 Z-2\n" +       // 6: tool 1, 2 mm in
                                         change +           // 7-9
                                         "G0 Z-3\n"         // 10: tool 2, 1 mm deeper
                                         "G0 Z5\nM30\n");
    const auto rapid = ofType(r, CollisionType::kRapidIntoStock);
    ASSERT_EQ(rapid.size(), 2u);
    EXPECT_EQ(rapid[0]->tool, 1);
    EXPECT_EQ(rapid[0]->line, 6);
    EXPECT_EQ(rapid[0]->last_line, 6);
    EXPECT_NEAR(rapid[0]->depth, 2.0, 0.2);
    EXPECT_EQ(rapid[1]->tool, 2);
    EXPECT_EQ(rapid[1]->line, 10);
    EXPECT_EQ(rapid[1]->last_line, 10);
    EXPECT_NEAR(rapid[1]->depth, 1.0, 0.2);
    EXPECT_NEAR(rapid[1]->position.z, -2.0, 0.15);  // where tool 2 leaves the hole's floor
    EXPECT_EQ(r.collisions.size(), 2u);
  }
  {
    // The holder (30-40 mm above the tip) 1 mm into the stock top, then tool 2's 1.5 mm
    // (the cutter below the stock, the shank in its own hole).
    const Report r = run(twoTools(), std::string(kStart) +
                                         "M3 S9000\n"        // 4
                                         "G0 X20 Y20 Z5\n"   // 5
                                         "G1 Z-31 F200\n" +  // 6: tool 1's holder 1 mm in
                                         change +            // 7-9
                                         "G1 Z-31.5 F200\n"  // 10: tool 2's holder
                                         "G0 Z5\nM30\n");
    const auto holder = ofType(r, CollisionType::kHolderContact);
    ASSERT_EQ(holder.size(), 2u);
    EXPECT_EQ(holder[0]->tool, 1);
    EXPECT_EQ(holder[0]->line, 6);
    EXPECT_EQ(holder[0]->last_line, 6);
    EXPECT_NEAR(holder[0]->depth, 1.0, 0.2);
    EXPECT_EQ(holder[1]->tool, 2);
    EXPECT_EQ(holder[1]->line, 10);
    EXPECT_EQ(holder[1]->last_line, 11);  // the retract leaves the stock
    EXPECT_NEAR(holder[1]->depth, 1.5, 0.2);
    EXPECT_EQ(r.collisions.size(), 2u);
  }
}

TEST(Collisions, ShankInTheWallButNotInItsOwnHole) {
  Rig s;
  s.options.density = 5;
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S9000\n"          // 4
                                         "G0 X20 Y20 Z5\n"     // 5
                                         "G1 Z-12 F200\n"      // 6: shank follows the cutter
                                         "G1 X30 F400\n"       // 7: shank 2 mm into the wall
                                         "G1 X20\n"            // 8: and back in its slot
                                         "G0 Z5\nM5\nM30\n");  // 9: out through the hole
  ASSERT_EQ(r.collisions.size(), 1u);
  const Collision& c = r.collisions[0];
  EXPECT_EQ(c.type, CollisionType::kShankContact);
  EXPECT_EQ(c.part, ToolPartName::kShank);
  EXPECT_EQ(c.line, 7);
  // The shank starts 10 mm above the tip: material from z -2 to 0 inside it, whose
  // deepest point is 2 mm from the shank's lower end.
  EXPECT_NEAR(c.depth, 2.0, 0.25);
  EXPECT_NEAR(c.position.z, -12.0, 1e-9);
  EXPECT_EQ(c.last_line, 8);
}

TEST(Collisions, HolderBuriedByAPlunge) {
  Rig s;
  s.options.density = 5;
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S9000\n"
                                         "G0 X20 Y20 Z5\n"
                                         "G1 Z-18 F200\n"  // 6: holder (30 above the tip) at 12
                                         "G1 Z-33\n"       // 7: holder bottom at -3
                                         "G0 Z5\nM5\nM30\n");
  const auto holder = ofType(r, CollisionType::kHolderContact);
  ASSERT_EQ(holder.size(), 1u);
  EXPECT_EQ(holder[0]->line, 7);
  EXPECT_NEAR(holder[0]->position.z, -30.0, 0.2);  // holder meets the top at tip -30
  EXPECT_NEAR(holder[0]->depth, 3.0, 0.25);
  EXPECT_EQ(holder[0]->last_line, 8);  // the retract starts buried
  EXPECT_TRUE(ofType(r, CollisionType::kShankContact).empty());
}

// The holder's centre stays outside the stock's box, its rim 1 mm into the side: the
// sweep that finds it is still made (a part far from the stock gets none).
TEST(Collisions, HolderRimInTheSideFromOutsideTheStock) {
  Rig s;
  s.options.density = 5;
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S9000\n"          // 4
                                         "G0 X-9 Y20 Z5\n"     // 5: holder (r 10) over x -19..1
                                         "G1 Z-35 F500\n"      // 6: its bottom down to z -5
                                         "G1 Y25\n"            // 7: along the side
                                         "G0 Z5\nM5\nM30\n");  // 8
  const auto holder = ofType(r, CollisionType::kHolderContact);
  ASSERT_EQ(holder.size(), 1u);
  EXPECT_EQ(holder[0]->line, 6);
  EXPECT_EQ(holder[0]->last_line, 8);
  EXPECT_NEAR(holder[0]->position.z, -30.0, 0.25);  // the holder's bottom meets z 0
  EXPECT_GT(holder[0]->depth, 0.5);
  EXPECT_TRUE(ofType(r, CollisionType::kShankContact).empty());
  EXPECT_NEAR(r.stats.removed_volume_mm3, 0.0, 1e-9);  // contacts remove nothing
}

TEST(Collisions, ContactsShallowerThanTheToleranceAreNotCollisions) {
  Rig s;
  s.options.density = 5;
  s.options.contact_tolerance = 2.5;  // the shank's 2 mm in the wall is below it
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S9000\nG0 X20 Y20 Z5\nG1 Z-12 F200\nG1 X30 F400\n"
                                         "G0 Z5\nM5\nM30\n");
  EXPECT_TRUE(r.collisions.empty());
  EXPECT_EQ(r.status, Status::kClean);
}

// A contact tolerance below a quarter of the grid spacing (an mdhd option: any value
// >= 0) holds for contacts between it and h/4 too. The depth's pruning skipped every
// overlap whose bound was within h/4 of the depth found so far, 0 at the start: at
// density 5 (h/4 = 0.05) with a tolerance of 0.01 a rapid 0.03 mm into the stock top
// and a holder 0.03 mm in ran `clean` until session 23.
TEST(Collisions, ContactsBetweenASmallToleranceAndAQuarterSpacingAreCollisions) {
  for (const double tol : {0.0, 0.01}) {
    Rig s;
    s.options.density = 5;
    s.options.contact_tolerance = tol;
    const Report r = run(std::move(s), std::string(kStart) +
                                           "M3 S9000\n"         // 4
                                           "G0 X20 Y20 Z5\n"    // 5
                                           "G0 Z-0.03\n"        // 6: 0.03 mm in
                                           "G0 Z5\n"            // 7
                                           "G0 X10 Y10\n"       // 8
                                           "G1 Z-30.03 F200\n"  // 9: holder (30 mm up) 0.03 in
                                           "G0 Z5\n"            // 10
                                           "G0 X30 Y30\n"       // 11
                                           "G0 Z-0.005\n"       // 12: 0.005 mm: below 0.01
                                           "G0 Z5\nM30\n");
    SCOPED_TRACE(tol);
    const auto rapid = ofType(r, CollisionType::kRapidIntoStock);
    ASSERT_EQ(rapid.size(), tol == 0.0 ? 2u : 1u);
    EXPECT_EQ(rapid[0]->line, 6);
    EXPECT_NEAR(rapid[0]->depth, 0.03, 1e-6);  // a flat bottom: sampled where it lies
    if (tol == 0.0) {
      EXPECT_EQ(rapid[1]->line, 12);
    }
    const auto holder = ofType(r, CollisionType::kHolderContact);
    ASSERT_EQ(holder.size(), 1u);
    EXPECT_EQ(holder[0]->line, 9);
    EXPECT_NEAR(holder[0]->depth, 0.03, 1e-6);
    EXPECT_EQ(r.collisions.size(), rapid.size() + 1);
  }
}

// A thin tool dragged sideways through the stock: the shank's contact is as deep as
// its radius at every density (the depth lines once shared one stride between x and y,
// so a 10 mm move skipped the shank's middle line from 15 points/mm on and lost it).
TEST(Collisions, ThinShankDraggedThroughTheStockAtAnyDensity) {
  for (const double diameter : {0.15, 1.0}) {
    for (const double density : {7.0, 10.0, 15.0, 20.0, 30.0}) {
      Rig s;
      s.options.density = density;
      geom::Tool t = flatTool();
      t.diameter = t.shank_diameter = diameter;
      s.tools.push_back(t);
      const Report r = run(std::move(s), std::string(kStart) +
                                             "M3 S9000\nG0 X20 Y20 Z5\n"  // 4-5
                                             "G1 Z-15 F200\n"             // 6: the shank from -5 up
                                             "G1 X30 F400\n"              // 7: through 5 mm of wall
                                             "M5\nM30\n");
      const auto shank = ofType(r, CollisionType::kShankContact);
      ASSERT_EQ(shank.size(), 1u) << diameter << " mm at " << density << " points/mm";
      EXPECT_EQ(shank[0]->line, 7);
      EXPECT_NEAR(shank[0]->depth, diameter / 2, 1e-3) << diameter << " mm at " << density;
    }
  }
}

// A shank pushed sideways into the side of the stock in moves far shorter than a grid
// spacing keeps its height in the material while it goes deeper: the depth is how far
// in it went (once measured at the first contact's 0.1 mm and never again), whether the
// move comes in one block or in 50.
TEST(Collisions, ShankPushedSidewaysInShortMovesIsMeasuredAtItsDeepest) {
  for (const int moves : {1, 50}) {
    std::string program = std::string(kStart) +
                          "M3 S9000\nG0 X-3.5 Y20 Z5\n"  // 4-5: the shank's side 0.5 mm off x = 0
                          "G1 Z-15 F200\n";  // 6: the shank from -5 up, beside the stock
    for (int i = 1; i <= moves; ++i)
      program += "G1 X" + std::to_string(-3.5 + 2.5 * i / moves) + " F400\n";  // to X-1: 2 mm in
    const Report r = run(Rig{}, program + "G0 Z5\nM5\nM30\n");
    const auto shank = ofType(r, CollisionType::kShankContact);
    ASSERT_EQ(shank.size(), 1u) << moves;
    if (moves == 1) {
      EXPECT_EQ(shank[0]->line, 7);
    }
    EXPECT_EQ(shank[0]->last_line, 6 + moves);
    EXPECT_NEAR(shank[0]->depth, 2.0, 0.12) << moves << " moves";
  }
}

// Drilled holes' volumes against the closed form, for tips from 90 to 170 degrees: a
// blunt tip puts the wall's foot between grid levels, where the volume integral once
// walked a wall's crossings out of order (+0.75 % at 10 points/mm for 170 degrees).
TEST(Collisions, DrilledHolesRemoveTheirVolume) {
  for (const double angle : {90.0, 118.0, 170.0}) {
    Rig s;
    s.options.density = 10;
    geom::Tool t = flatTool();
    t.shape = geom::ToolShape::kDrill;
    t.tip_angle = angle;
    s.tools.push_back(t);
    const Report r =
        run(std::move(s),
            std::string(kStart) + "M3 S9000\nG0 X20 Y20 Z5\nG1 Z-10 F300\nG0 Z5\nM5\nM30\n");
    const double h = 3 / std::tan(angle / 2 * pi / 180);  // the cone's height
    const double hole = pi * 9 * (10 - h) + pi * 9 * h / 3;
    EXPECT_NEAR(r.stats.removed_volume_mm3, hole, 0.004 * hole) << angle << " degrees";
    EXPECT_EQ(r.status, Status::kClean);
  }
}

// Passes whose cutter runs exactly tangent to the stock's sides (X-3 and Y43 with a
// 6 mm end mill: CAM's usual finishing pass on a stock cut to size) remove nothing.
// The line where a plunge touches a side lies on the tool's surface, so its column
// dropped while every row beside it kept its solid, and the volume grew by a quarter
// of the drop per square: `removed_volume_mm3` read -0.4 at density 5 and -0.1 at 10
// until session 23. (Two tangent passes meeting at the stock's corner still read
// 0.1 mm3 removed at density 5, and so do flutes ending exactly at the stock's top
// along a tangent side: two tangent planes meeting on a grid line; docs/engine.md.)
TEST(Collisions, AToolTangentToTheStocksSidesRemovesNothing) {
  for (const double density : {5.0, 10.0}) {
    Rig s;
    s.options.density = density;
    s.tools.push_back(flatTool());
    s.tools.back().flute_length = 20;  // the flutes' top stays above the stock
    const Report r = run(std::move(s), std::string(kStart) +
                                           "M3 S9000\nG0 X-3 Y20 Z5\nG1 Z-10 F300\nG1 Y35\n"
                                           "G0 Z5\nG0 X20 Y43\nG1 Z-10\nG1 X30\nG0 Z5\nM5\nM30\n");
    EXPECT_NEAR(r.stats.removed_volume_mm3, 0.0, 1e-9) << density << " points/mm";
    EXPECT_NEAR(r.stats.final_volume_mm3, 40.0 * 40 * 20, 1e-9) << density << " points/mm";
    EXPECT_EQ(r.status, Status::kClean);
  }
}

// No contact of a part narrower than twice the contact tolerance could be reported
// (nothing lies deeper in it than its radius): its first motion is an error, not a
// "clean" run. A tool in the table that the program never uses blocks nothing.
TEST(Collisions, ToolTooThinForTheContactToleranceIsAnErrorAtItsFirstMove) {
  const auto rig = [](double cutter, double shank) {
    Rig s;
    s.options.density = 5;  // contact tolerance 0.1 mm
    s.tools.push_back(flatTool(1));
    geom::Tool thin = flatTool(2);
    thin.diameter = cutter;
    thin.shank_diameter = shank;
    s.tools.push_back(thin);
    return s;
  };
  const std::string program = "G21 G90 G17\nT2 M6\nG43 H2\nM3 S9000\nG0 X20 Y20 Z5\nG0 Z-1\nM30\n";
  for (const auto& [cutter, shank, part] :
       {std::tuple{0.2, 1.0, "cutter"}, std::tuple{1.0, 0.15, "shank"}}) {
    try {
      run(rig(cutter, shank), program);
      ADD_FAILURE() << "a " << part << " too thin to report was simulated";
    } catch (const gcode::GcodeError& e) {
      EXPECT_EQ(e.pos().line, 5);
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string("tool 2's ") + part), std::string::npos) << what;
      EXPECT_NE(what.find("options.density above"), std::string::npos) << what;
    }
  }
  // Tool 1 only: the thin tool 2 in the table is never loaded.
  const Report r =
      run(rig(0.2, 1.0), std::string(kStart) + "M3 S9000\nG0 X20 Y20 Z5\nG0 Z-1\nM30\n");
  ASSERT_EQ(r.collisions.size(), 1u);
  EXPECT_EQ(r.collisions[0].type, CollisionType::kRapidIntoStock);
}

TEST(Collisions, CutterIntoAFixtureBelowTheStock) {
  Rig s;
  s.options.density = 5;
  s.fixtures.push_back(
      std::make_unique<geom::BoxSolid>(glm::dvec3(-10, -10, -30), glm::dvec3(50, 50, -20)));
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S9000\nG0 X20 Y20 Z5\n"
                                         "G1 Z-21 F200\n"  // 6: 1 mm into the vise
                                         "G0 Z5\nM5\nM30\n");
  const auto f = ofType(r, CollisionType::kFixtureContact);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0]->line, 6);
  EXPECT_EQ(f[0]->part, ToolPartName::kCutter);
  EXPECT_EQ(f[0]->fixture, 0);
  EXPECT_NEAR(f[0]->depth, 1.0, 0.1);
  // First contact: where the penetration first exceeds the contact tolerance (0.1 mm).
  EXPECT_NEAR(f[0]->position.z, -20.1, 0.02);
  // The fixture is not machinable: only the stock lost material.
  EXPECT_NEAR(r.stats.removed_volume_mm3, pi * 9 * 20, 0.02 * pi * 9 * 20);
}

TEST(Collisions, RapidThroughAClampCylinder) {
  Rig s;
  s.options.density = 5;
  s.fixtures.push_back(std::make_unique<geom::CylinderSolid>(glm::dvec3(60, 20, -20),
                                                             glm::dvec3(0, 0, 1), 5.0, 30.0));
  const Report r =
      run(std::move(s), std::string(kStart) +
                            "M3 S9000\nG0 X20 Y20 Z5\n"
                            "G0 X80\n"  // 6: the cutter (z 5..15) through the clamp top
                            "G0 Z50\nM5\nM30\n");
  ASSERT_EQ(r.collisions.size(), 1u);
  const Collision& c = r.collisions[0];
  EXPECT_EQ(c.type, CollisionType::kFixtureContact);
  EXPECT_EQ(c.line, 6);
  EXPECT_EQ(c.part, ToolPartName::kCutter);
  // The cutter's edge meets the clamp's side, plus the contact tolerance (0.1 mm).
  EXPECT_NEAR(c.position.x, 60 - 5 - 3 + 0.1, 0.03);
  EXPECT_NEAR(c.depth, 3.0, 0.25);  // clamp top 5 mm up the 3 mm radius cutter
}

TEST(Collisions, AxisLimitEpisodesAndHowFarBeyond) {
  Rig s;
  s.options.density = 2;
  const Report r = run(std::move(s),
                       "G21 G90\nT1 M6\nG43 H1\n"
                       "G0 X450\n"   // 4: X limit is 400
                       "G0 X420\n"   // 5: still beyond: same episode
                       "G0 X0\n"     // 6: back (the path starts beyond)
                       "G0 X10\n"    // 7: inside
                       "G0 X-410\n"  // 8: a new episode at the other end
                       "M30\n");
  const auto lim = ofType(r, CollisionType::kAxisLimit);
  ASSERT_EQ(lim.size(), 2u);
  EXPECT_EQ(lim[0]->line, 4);
  EXPECT_EQ(lim[0]->last_line, 6);
  EXPECT_EQ(lim[0]->axis, "X");
  EXPECT_NEAR(lim[0]->depth, 50.0, 1e-9);
  EXPECT_NEAR(lim[0]->joints[gcode::kX], 400.0, 1e-6);  // where it first leaves its range
  EXPECT_EQ(lim[1]->line, 8);
  EXPECT_NEAR(lim[1]->depth, 10.0, 1e-9);
  EXPECT_EQ(r.collisions.size(), 2u);
}

// A joint that goes from below its min to beyond its max in one move leaves one
// overtravel and starts another: each side is its own episode, with its own line,
// depth and place. Until session 23 the side was not part of the episode: lines 4-8
// were one entry at line 4, 50 deep (line 5's), at X-400, and the +X overtravel of line
// 5 and the -X one of line 7 were never named.
TEST(Collisions, AxisLimitFromOneSideToTheOtherIsTwoEpisodes) {
  Rig s;
  s.options.density = 2;
  const Report r = run(std::move(s),
                       "G21 G90\nT1 M6\nG43 H1\n"
                       "G0 X-410\n"  // 4: X min is -400: 10 below
                       "G0 X450\n"   // 5: from 10 below min to 50 beyond max
                       "G0 X420\n"   // 6: still beyond max
                       "G0 X-430\n"  // 7: from beyond max to 30 below min
                       "G0 X0\n"     // 8: back inside
                       "M30\n");
  const auto lim = ofType(r, CollisionType::kAxisLimit);
  ASSERT_EQ(lim.size(), 3u);
  auto at = [&](std::size_t i, int line, int last, const char* block, double depth, double x) {
    SCOPED_TRACE(i);
    EXPECT_EQ(lim[i]->line, line);
    EXPECT_EQ(lim[i]->last_line, last);
    EXPECT_EQ(lim[i]->block, block);
    EXPECT_EQ(lim[i]->axis, "X");
    EXPECT_NEAR(lim[i]->depth, depth, 1e-9);
    EXPECT_NEAR(lim[i]->joints[gcode::kX], x, 1e-6);  // where it first leaves that side
  };
  at(0, 4, 5, "G0 X-410", 10, -400);
  at(1, 5, 7, "G0 X450", 50, 400);
  at(2, 7, 8, "G0 X-430", 30, -400);
  EXPECT_EQ(r.collisions.size(), 3u);
}

// A move to X 1e300 (300 digits) is an overtravel of about 1e300 mm on a path about as
// long: the tip's chord was measured through its squares, which overflow beyond ~1e154,
// and the path length was infinite (0 in the report) until session 23.
TEST(Collisions, AMoveFarBeyondTheLimitsHasAFinitePathAndDepth) {
  Rig s;
  s.options.density = 2;
  const Report r =
      run(std::move(s), "G21 G90\nT1 M6\nG43 H1\nG0 X" + std::string(300, '9') + "\nM30\n");  // 4
  const auto lim = ofType(r, CollisionType::kAxisLimit);
  ASSERT_EQ(lim.size(), 1u);
  EXPECT_EQ(lim[0]->line, 4);
  EXPECT_EQ(lim[0]->axis, "X");
  EXPECT_NEAR(lim[0]->depth / 1e300, 1.0, 1e-9);
  EXPECT_TRUE(std::isfinite(r.stats.path_length));
  EXPECT_NEAR(r.stats.path_length / 1e300, 1.0, 1e-9);
}

// Each joint beyond its range is its own episode, also when another joint left first
// in the same move, and an overtravel after the joint came back inside is a new one.
// Until session 22 only the earliest joint of a move was looked at: X of line 4 was
// reported at line 5, A of line 6 never, and lines 9 and 10 were one episode.
TEST(Collisions, AxisLimitEveryJointOfAMoveAndEveryReturnInside) {
  Rig s;
  s.machine = kin::presets::acTrunnion();  // X +-400, Y +-300, A -120..30
  s.options.density = 2;
  const Report r = run(std::move(s),
                       "G21 G90 G17\nT1 M6\n"
                       "G0 Z100\n"                   // 3
                       "G0 X500 Y400\n"              // 4: Y leaves at s 0.75, X at 0.8
                       "G0 X0 Y0\n"                  // 5: both back inside
                       "G0 X500 A-130\n"             // 6: X at s 0.8, A at 12/13
                       "G0 X390 Y-15 A0\n"           // 7: both back inside
                       "G3 X390 Y15 I0 J15 F1000\n"  // 8: bulges to X405 and back
                       "G2 X390 Y-15 I0 J-15\n"      // 9: again: a new episode
                       "M30\n");
  const auto lim = ofType(r, CollisionType::kAxisLimit);
  ASSERT_EQ(lim.size(), 6u);
  auto at = [&](std::size_t i, int line, int last, const char* axis, double depth) {
    SCOPED_TRACE(i);
    EXPECT_EQ(lim[i]->line, line);
    EXPECT_EQ(lim[i]->last_line, last);
    EXPECT_EQ(lim[i]->axis, axis);
    EXPECT_NEAR(lim[i]->depth, depth, 1e-6);
  };
  at(0, 4, 5, "Y", 100);
  at(1, 4, 5, "X", 100);
  at(2, 6, 7, "X", 100);
  at(3, 6, 7, "A", 10);
  at(4, 8, 8, "X", 5);
  at(5, 9, 9, "X", 5);
  // Where each first leaves: X375 Y300; X400 Y320; X400 A-104; A-120 X461.54.
  EXPECT_NEAR(lim[0]->joints[gcode::kX], 375, 1e-6);
  EXPECT_NEAR(lim[1]->joints[gcode::kY], 320, 1e-6);
  EXPECT_NEAR(lim[2]->joints[gcode::kA], -104, 1e-6);
  EXPECT_NEAR(lim[3]->joints[gcode::kX], 500.0 * 12 / 13, 1e-6);
  // On the arcs X reaches 400 where Y = -+sqrt(15^2 - 10^2).
  EXPECT_NEAR(lim[4]->joints[gcode::kY], -std::sqrt(125.0), 1e-6);
  EXPECT_NEAR(lim[5]->joints[gcode::kY], std::sqrt(125.0), 1e-6);
}

// 5-axis: an AC trunnion (W at the table centre) turns the part under a standing tool.
Rig trunnion() {
  Rig s;
  s.machine = kin::presets::acTrunnion();
  s.stock = {{-10, -10, 0}, {10, 10, 10}};
  s.options.density = 5;
  return s;
}

TEST(Collisions, TableTurnsThePartIntoAToolWithTheSpindleOff) {
  const Report r = run(trunnion(), std::string(kStart) +
                                       "G0 X16 Y0 Z5\n"  // 4: tip beside the part
                                       "G1 C60 F3600\n"  // 5: the corner swings into it
                                       "M30\n");
  const auto off = ofType(r, CollisionType::kSpindleOffCut);
  ASSERT_EQ(off.size(), 1u);
  EXPECT_EQ(off[0]->line, 5);
  // In W the tip runs on a circle of radius 16 about the C axis.
  EXPECT_NEAR(std::hypot(off[0]->position.x, off[0]->position.y), 16.0, 1e-6);
  EXPECT_NEAR(off[0]->position.z, 5.0, 1e-9);
  EXPECT_GT(off[0]->joints[gcode::kC], 0.0);
  EXPECT_LT(off[0]->joints[gcode::kC], 60.0);
  EXPECT_GT(r.stats.removed_volume_mm3, 0.0);
  // The tip's path in W: from home (tip at z 260) to the start, then the 60 degree arc
  // within the chordal tolerance.
  EXPECT_NEAR(r.stats.path_length, std::hypot(16.0, 255.0) + 16.0 * pi / 3, 0.01);
}

// The table turns a corner of the part into the tool's shank: the depth is how far the
// corner went in at its deepest (C45), not the first sliver of a contact that then only
// slides along its own height in the material (0.2 mm once, for 2.28).
TEST(Collisions, TableTurnsACornerIntoTheShank) {
  Rig s = trunnion();
  s.stock = {{-20, -20, 0}, {20, 20, 30}};
  s.options.density = 10;
  geom::Tool t = flatTool();
  t.diameter = 2;
  t.flute_length = 5;
  t.shank_diameter = 8;
  t.length = 60;
  s.tools.push_back(t);
  const Report r =
      run(std::move(s), std::string(kStart) +
                            "M3 S8000\nG0 X30 Y0 Z50\n"  // 4-5: the shank's axis 30 from C
                            "G1 Z10 F500\n"              // 6: the cutter clear (31 > 28.3)
                            "G1 C90 F3600\n"             // 7: the corner passes at C45
                            "G0 Z100\nM5\nM30\n");
  const auto shank = ofType(r, CollisionType::kShankContact);
  ASSERT_EQ(shank.size(), 1u);
  EXPECT_EQ(shank[0]->line, 7);
  EXPECT_NEAR(shank[0]->depth, 4.0 - (30.0 - 20.0 * std::sqrt(2.0)), 0.12);  // 2.28
  EXPECT_TRUE(ofType(r, CollisionType::kRapidIntoStock).empty());
}

// A rapid turn of the table swings the part over the whole cutter: the depth is the
// cutter's radius, measured against the material the motion met, not the slivers its
// earlier steps left (the finer the steps, the shallower it read: 1.06 for 4).
TEST(Collisions, RapidTurnBuriesTheWholeCutter) {
  for (const int steps : {0, 100}) {
    Rig s = trunnion();
    s.stock = {{-20, -20, 0}, {20, 20, 30}};
    s.options.density = 10;
    s.options.steps = steps;
    geom::Tool t = flatTool();
    t.diameter = t.shank_diameter = 8;
    t.flute_length = 30;
    t.length = 60;
    s.tools.push_back(t);
    const Report r = run(std::move(s), std::string(kStart) +
                                           "M3 S8000\nG0 X0 Y30 Z60\n"  // 4-5
                                           "G0 Z10\n"                   // 6: beside the +Y face
                                           "G0 A-45\n"                  // 7: the part turns over it
                                           "G0 Z100\nM5\nM30\n");
    const auto rapid = ofType(r, CollisionType::kRapidIntoStock);
    ASSERT_EQ(rapid.size(), 1u) << steps;
    EXPECT_EQ(rapid[0]->line, 7);
    EXPECT_NEAR(rapid[0]->depth, 4.0, 0.15) << steps << " steps";
  }
}

// A turn of the table too long for the step budget is an error at its line, not a cut
// whose last pieces are chords far off the arc (C1000000 removed 44 % too much); a
// long turn within the budget is simulated.
TEST(Collisions, TurnTooLongForTheStepBudgetIsAnErrorAtItsLine) {
  const std::string start = std::string(kStart) + "M3 S8000\nG0 X16 Y0 Z5\nG1 Z8 F500\n";
  try {
    run(trunnion(), start + "G1 C1000000 F360000\nM30\n");  // line 7
    ADD_FAILURE() << "simulated";
  } catch (const gcode::GcodeError& e) {
    EXPECT_EQ(e.pos().line, 7);
    EXPECT_EQ(e.pos().column, 1);  // the block's first word
    EXPECT_NE(std::string(e.what()).find("split it into shorter moves"), std::string::npos)
        << e.what();
  }
  const Report r = run(trunnion(), start + "G1 C3600 F360000\nM30\n");
  EXPECT_EQ(r.status, Status::kClean);
}

TEST(Collisions, TiltedRapidIntoTheSideFace) {
  // A-90 turns the part's -Y face up (the side drill's convention: tool axis -Y in W).
  const Report r = run(trunnion(), std::string(kStart) +
                                       "M3 S8000\n"
                                       "G0 A-90 C0\n"    // 5
                                       "G0 X0 Y5 Z25\n"  // 6: tip 15 mm off the face
                                       "G0 Z8\n"         // 7: 2 mm into it, rapid
                                       "G0 Z25\nM5\nM30\n");
  const auto rapid = ofType(r, CollisionType::kRapidIntoStock);
  ASSERT_EQ(rapid.size(), 1u);
  EXPECT_EQ(rapid[0]->line, 7);
  EXPECT_NEAR(rapid[0]->depth, 2.0, 0.25);
  EXPECT_NEAR(rapid[0]->position.y, -10.0, 0.15);  // first contact on the -Y face
  EXPECT_EQ(r.collisions.size(), 1u);
}

// A hole drilled along a tool tilted 45 degrees under G43.4, then G49 and a retract
// that names Z only: the machine's X and Y stay where they are (G49 once put them at
// the tip's W coordinates, dragging the tool sideways through the part: a false rapid
// and holder contact and three times the volume).
TEST(Collisions, RetractAfterLeavingG43_4KeepsTheUnnamedAxes) {
  Rig s = trunnion();
  s.options.density = 10;
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S8000\n"
                                         "G0 A-45 C0\n"                      // 5
                                         "G43.4 H1\n"                        // 6
                                         "G0 X0 Y-3.535534 Z13.535534\n"     // 7: 5 mm off
                                         "G1 X0 Y7.071068 Z2.928932 F200\n"  // 8: 10 deep
                                         "G0 X0 Y-3.535534 Z13.535534\n"     // 9: back out
                                         "G49\n"                             // 10
                                         "G91 G0 Z30\n"                      // 11: straight up
                                         "G90 M5\nM30\n");
  EXPECT_EQ(r.status, Status::kClean);
  EXPECT_TRUE(r.collisions.empty());
  // A tilted plane cuts the cylinder symmetrically about its axis: pi r^2 x 10.
  EXPECT_NEAR(r.stats.removed_volume_mm3, pi * 9 * 10, 0.015 * pi * 9 * 10);
}

TEST(Collisions, HolderOnA5AxisTilt) {
  // A short tool drilling into the tilted part's face until its holder meets the face.
  Rig s = trunnion();
  geom::Tool t = flatTool();
  t.length = 20;
  t.flute_length = 8;
  t.holder = {{20, 8}};  // holder from 12 mm above the tip
  s.tools = {t};
  const Report r = run(std::move(s), std::string(kStart) +
                                         "M3 S8000\nG0 A-90 C0\nG0 X0 Y5 Z25\n"
                                         "G1 Z-4 F200\n"  // 7: tip 14 deep: holder 2 mm in
                                         "G0 Z25\nM5\nM30\n");
  const auto holder = ofType(r, CollisionType::kHolderContact);
  ASSERT_EQ(holder.size(), 1u);
  EXPECT_EQ(holder[0]->line, 7);
  EXPECT_NEAR(holder[0]->depth, 2.0, 0.25);
  // The shank (as wide as the cutter) follows it down its own hole: no contact.
  EXPECT_TRUE(ofType(r, CollisionType::kShankContact).empty());
  EXPECT_EQ(r.collisions.size(), 1u);
}

TEST(Collisions, CancelFlagStopsTheRun) {
  std::atomic<bool> cancel{true};
  EXPECT_THROW(run(Rig{}, std::string(kStart) + "G0 X1\nM30\n", &cancel), Cancelled);
}

}  // namespace
}  // namespace mdhd::check

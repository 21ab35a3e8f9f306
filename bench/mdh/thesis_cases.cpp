#include "bench/mdh/thesis_cases.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace mdhd::mdh::bench {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadius = 0.15;  // table 6.8's tool; the thesis names no other

geom::Tool tool(geom::ToolShape shape) {
  geom::Tool t;
  t.number = 1;
  t.shape = shape;
  t.diameter = 2 * kRadius;
  t.shank_diameter = 2 * kRadius;
  t.flute_length = 6.0;  // longer than any stock here: the whole tool cuts, as in the thesis
  t.length = 8.0;
  return t;
}

geom::Aabb cube(double side) {
  return {{0, 0, 0}, {side, side, side}};
}

// The tip of a ball tool whose sphere is centred at c.
glm::dvec3 ballTip(glm::dvec3 c, glm::dvec3 axis) {
  return c - kRadius * axis;
}

// Straight plunge along the tool's own axis from `lift` above the pose into it.
void plunge(std::vector<Motion>& out, const geom::ToolPose& p, double lift) {
  out.push_back({{p.tip + lift * p.axis, p.axis}, p});
}

void chain(std::vector<Motion>& out, const std::vector<geom::ToolPose>& poses) {
  for (std::size_t i = 0; i + 1 < poses.size(); ++i) out.push_back({poses[i], poses[i + 1]});
}

// A ball tool leaning `tilt` towards the vertical axis through (cx, cy), its
// sphere's centre on a path around that axis: radius r0 -> r1 and height
// z0 -> z1 over `turns`, one motion per `degrees` (figure 6.13's surface).
std::vector<Motion> donut(double tilt, double cx, double cy, double r0, double r1, double z0,
                          double z1, double turns, double degrees) {
  const int n = std::max(1, static_cast<int>(std::lround(turns * 360 / degrees)));
  std::vector<geom::ToolPose> poses;
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n, phi = 2 * kPi * turns * t;
    const glm::dvec3 d{std::cos(phi), std::sin(phi), 0};
    const glm::dvec3 axis = -std::sin(tilt) * d + std::cos(tilt) * glm::dvec3{0, 0, 1};
    const glm::dvec3 c = glm::dvec3{cx, cy, z0 + (z1 - z0) * t} + (r0 + (r1 - r0) * t) * d;
    poses.push_back({ballTip(c, axis), axis});
  }
  std::vector<Motion> out;
  plunge(out, poses.front(), 1.0);
  chain(out, poses);
  return out;
}

ThesisCase cylinderSpiral() {
  // CS: a horizontal ball tool pointing at a vertical core spirals down around
  // it; the pitch (0.35 mm) is wider than the tool (0.3 mm), leaving a thin
  // helical fin that overhangs in every direction.
  ThesisCase c{"CS", {{0, 0, 0}, {2, 2, 1.5}}, tool(geom::ToolShape::kBall), {}, ""};
  c.guess = "stock 2x2x1.5 (from the pointer-grid size), core radius 0.6, 3 turns, pitch 0.35";
  const int n = 3 * 72;
  std::vector<geom::ToolPose> poses;
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n, phi = 6 * kPi * t;
    const glm::dvec3 d{std::cos(phi), std::sin(phi), 0};
    poses.push_back({glm::dvec3{1, 1, 1.35 - 1.05 * t} + 0.6 * d, d});
  }
  c.motions.push_back(
      {{poses.front().tip + 1.0 * poses.front().axis, poses.front().axis}, poses.front()});
  chain(c.motions, poses);
  return c;
}

ThesisCase drillEdge(bool connected) {
  // MA: three drillings into the top face, then a 45-degree ball cut along the
  // top +x edge; in MA1 the drill holes reach the edge cut, in MA2 they do not.
  ThesisCase c{connected ? "MA1" : "MA2", cube(1), tool(geom::ToolShape::kBall), {}, ""};
  c.guess = "1 mm cube; drills at x = 0.8 / 0.5, y = 0.25, 0.5, 0.75, 0.4 deep";
  const double x = connected ? 0.8 : 0.5;
  for (double y : {0.25, 0.5, 0.75}) plunge(c.motions, {{x, y, 0.6}, {0, 0, 1}}, 0.6);
  const glm::dvec3 axis = glm::normalize(glm::dvec3{1, 0, 1});
  c.motions.push_back(
      {{ballTip({0.92, -0.3, 0.82}, axis), axis}, {ballTip({0.92, 1.3, 0.82}, axis), axis}});
  return c;
}

// A ball drilled along `axis` until its tip reaches `bottom`.
ThesisCase drill(std::string name, double side, glm::dvec3 axis, glm::dvec3 bottom,
                 std::string guess) {
  ThesisCase c{std::move(name), cube(side), tool(geom::ToolShape::kBall), {}, std::move(guess)};
  plunge(c.motions, {bottom, glm::normalize(axis)}, 0.8 * side);
  return c;
}

ThesisCase planarCuts() {
  // A3: a flat end mill's face machines a plane into the top, then into the -x side.
  ThesisCase c{"A3", cube(1), tool(geom::ToolShape::kFlat), {}, ""};
  c.guess = "1 mm cube; top face at z = 0.8 over x < 0.6, side face at x = 0.3 over z < 0.3";
  for (double y = 0; y <= 1.0001; y += 0.2)
    c.motions.push_back({{{-0.3, y, 0.8}, {0, 0, 1}}, {{0.6, y, 0.8}, {0, 0, 1}}});
  for (double y = 0; y <= 1.0001; y += 0.2)
    c.motions.push_back({{{0.3, y, -0.3}, {-1, 0, 0}}, {{0.3, y, 0.3}, {-1, 0, 0}}});
  return c;
}

}  // namespace

std::vector<ThesisCase> thesisCases(double donutDegrees) {
  const geom::Aabb plate{{0, 0, 0}, {4, 4, 1}};
  const double d25 = 25 * kPi / 180, d45 = 45 * kPi / 180, zT = 0.6748;
  const std::string fromTable = "table 6.8 (stock, tool, torus); ";
  std::vector<ThesisCase> cases;
  cases.push_back(cylinderSpiral());
  auto ball = tool(geom::ToolShape::kBall);
  cases.push_back({"D1", plate, ball, donut(d25, 2, 2, 1.69, 1.69, zT, zT, 1, donutDegrees),
                   fromTable + "one turn"});
  cases.push_back({"D2", plate, ball, donut(d45, 2, 2, 1.69, 1.69, zT, zT, 1, donutDegrees),
                   fromTable + "45 degrees instead of 25"});
  // DS: the spiral's pitch is lost with figures 6.4/6.5. Four turns (0.1975 mm,
  // two thirds of the tool's diameter: cusps 0.037 mm high) put random
  // selection at 0.87x / 1.05x table 6.2's RS row; 3 turns gave 2.6x / 2.8x,
  // with cusps 0.078 mm high that need fallback halvings the thesis never had.
  constexpr double kSpiralTurns = 4;
  cases.push_back({"DS1", plate, ball,
                   donut(d25, 2, 2, 1.69, 0.9, zT, zT, kSpiralTurns, donutDegrees),
                   fromTable + "spiral in to radius 0.9 over 4 turns (pitch from RS)"});
  cases.push_back({"DS2", plate, ball,
                   donut(d45, 2, 2, 1.69, 0.9, zT, zT, kSpiralTurns, donutDegrees),
                   fromTable + "45 degrees, spiral in to radius 0.9 over 4 turns"});
  cases.push_back(drillEdge(true));
  cases.push_back(drillEdge(false));
  cases.push_back(drill("NA", 1, {1, 1, std::sqrt(2.0)}, {0.5, 0.5, 0.7},
                        "1 mm cube, 0.3 mm deep at the top face's centre"));
  cases.push_back(drill("A1", 1, {std::sin(kPi / 6), 0, std::cos(kPi / 6)}, {0.5, 0.5, 0.6},
                        "1 mm cube, 30 degrees, 0.4 mm deep"));
  {  // A2: drills from the -x, -y and +z faces meet at the centre.
    ThesisCase c{"A2", cube(2), ball, {}, "2 mm cube (from the pointer-grid size)"};
    for (glm::dvec3 axis : {glm::dvec3{-1, 0, 0}, glm::dvec3{0, -1, 0}, glm::dvec3{0, 0, 1}})
      plunge(c.motions, {glm::dvec3(1.0), axis}, 1.3);
    cases.push_back(std::move(c));
  }
  cases.push_back(planarCuts());
  return cases;
}

}  // namespace mdhd::mdh::bench

#include "bench/mdh/thesis_cases.h"

#include <cmath>
#include <numbers>

#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh::bench {

namespace {

using testing::CapsuleSolid;
using testing::CylinderSolid;

constexpr double kPi = std::numbers::pi;
const geom::Aabb kCube{{0, 0, 0}, {10, 10, 10}};

Step ball(glm::dvec3 tip, glm::dvec3 dir, double r) {
  dir = glm::normalize(dir);
  return {std::make_shared<CapsuleSolid>(tip, tip + 20.0 * dir, r), dir, r};
}

Step flat(glm::dvec3 tip, glm::dvec3 dir, double r) {
  dir = glm::normalize(dir);
  return {std::make_shared<CylinderSolid>(tip, dir, r, 20.0), dir, r};
}

// Straight move of a ball tool with fixed orientation, stamped.
void line(std::vector<Step>& out, glm::dvec3 a, glm::dvec3 b, glm::dvec3 dir, double r,
          double perMm, bool isBall = true) {
  const int n = std::max(1, static_cast<int>(std::ceil(glm::length(b - a) * perMm)));
  for (int i = 0; i <= n; ++i) {
    const glm::dvec3 p = a + (b - a) * (double(i) / n);
    out.push_back(isBall ? ball(p, dir, r) : flat(p, dir, r));
  }
}

// A tool tilted by `tilt` away from +z (leaning outwards), its tip on a
// circle/helix around the cube's vertical axis.
ThesisCase donut(std::string name, double tilt, double radius, double z0, double z1, double turns,
                 double perMm) {
  ThesisCase c{std::move(name), kCube, {}};
  const int n = static_cast<int>(std::ceil(2 * kPi * radius * turns * perMm));
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n, phi = 2 * kPi * turns * t;
    const glm::dvec3 radial{std::cos(phi), std::sin(phi), 0};
    const glm::dvec3 tip = glm::dvec3{5, 5, z0 + (z1 - z0) * t} + radius * radial;
    c.steps.push_back(
        ball(tip, std::sin(tilt) * radial + std::cos(tilt) * glm::dvec3{0, 0, 1}, 0.8));
  }
  return c;
}

}  // namespace

std::vector<ThesisCase> thesisCases(double perMm) {
  std::vector<ThesisCase> cases;
  {  // CS: a horizontal tool pointing outwards spirals down around a core.
    ThesisCase c{"CS", kCube, {}};
    const double turns = 3, radius = 3.2;
    const int n = static_cast<int>(std::ceil(2 * kPi * radius * turns * perMm));
    for (int i = 0; i <= n; ++i) {
      const double t = double(i) / n, phi = 2 * kPi * turns * t;
      const glm::dvec3 radial{std::cos(phi), std::sin(phi), 0};
      c.steps.push_back(ball(glm::dvec3{5, 5, 9 - 7 * t} + radius * radial, radial, 1.0));
    }
    cases.push_back(std::move(c));
  }
  cases.push_back(donut("D1", 25 * kPi / 180, 3.0, 7.0, 7.0, 1, perMm));
  cases.push_back(donut("D2", 45 * kPi / 180, 3.0, 7.0, 7.0, 1, perMm));
  cases.push_back(donut("DS1", 25 * kPi / 180, 3.0, 9.0, 6.0, 3, perMm));
  cases.push_back(donut("DS2", 45 * kPi / 180, 3.0, 9.0, 6.0, 3, perMm));
  for (int variant = 1; variant <= 2; ++variant) {
    // MA: three drills into the top face, then an angled cut along the top
    // +x edge; in MA1 the drills reach the edge cut, in MA2 they stop short.
    ThesisCase c{variant == 1 ? "MA1" : "MA2", kCube, {}};
    const double x = variant == 1 ? 8.0 : 5.5;
    for (double y : {2.5, 5.0, 7.5})
      line(c.steps, {x, y, 11}, {x, y, 7}, {0, 0, 1}, 0.8, perMm, false);
    const glm::dvec3 tilt = glm::normalize(glm::dvec3{1, 0, 1});
    line(c.steps, {9.2, -1, 8.2}, {9.2, 11, 8.2}, tilt, 1.0, perMm);
    cases.push_back(std::move(c));
  }
  {  // NA: a drill at 45 degrees from z in a plane at 45 degrees to x and y.
    ThesisCase c{"NA", kCube, {}};
    const glm::dvec3 dir = glm::normalize(glm::dvec3{1, 1, std::sqrt(2.0)});
    line(c.steps, glm::dvec3{5, 5, 10} + 1.5 * dir, glm::dvec3{5, 5, 10} - 3.0 * dir, dir, 0.8,
         perMm);
    cases.push_back(std::move(c));
  }
  {  // A1: angled drilling aligned with the x-z plane.
    ThesisCase c{"A1", kCube, {}};
    const glm::dvec3 dir = glm::normalize(glm::dvec3{std::sin(kPi / 6), 0, std::cos(kPi / 6)});
    line(c.steps, glm::dvec3{5, 5, 10} + 1.0 * dir, glm::dvec3{5, 5, 10} - 4.0 * dir, dir, 0.8,
         perMm);
    cases.push_back(std::move(c));
  }
  {  // A2: a drill from the -x, -y and +z faces to the centre.
    ThesisCase c{"A2", kCube, {}};
    for (glm::dvec3 dir : {glm::dvec3{-1, 0, 0}, glm::dvec3{0, -1, 0}, glm::dvec3{0, 0, 1}})
      line(c.steps, glm::dvec3(5.0) + 6.0 * dir, glm::dvec3(5.0), dir, 0.8, perMm);
    cases.push_back(std::move(c));
  }
  {  // A3: two planar cuts with a flat end mill's face (top, then -x side).
    ThesisCase c{"A3", kCube, {}};
    for (double y = 0; y <= 10; y += 1.0)
      line(c.steps, {-2, y, 8}, {6, y, 8}, {0, 0, 1}, 1.0, perMm, false);
    for (double y = 0; y <= 10; y += 1.0)
      line(c.steps, {3, y, -2}, {3, y, 3}, {-1, 0, 0}, 1.0, perMm, false);
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace mdhd::mdh::bench

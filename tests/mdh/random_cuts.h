#pragma once
// Random 5-axis cut sequences for the reference tests: ball and flat end
// mills with their shanks, any tilt (from below too), stamped along straight
// moves through the stock.
#include <memory>
#include <random>
#include <vector>

#include "tests/mdh/analytic_solids.h"

namespace mdhd::mdh::testing {

struct Stamp {
  std::shared_ptr<geom::LineSolid> solid;
  glm::dvec3 direction;  // tip to spindle
  double radius;
};

inline glm::dvec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  glm::dvec3 d(n(rng), n(rng), n(rng));
  return glm::normalize(d);
}

inline std::vector<Stamp> randomCuts(std::uint64_t seed, const geom::Aabb& box, int moves,
                                     int stampsPerMove) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Stamp> out;
  auto inside = [&] {
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a)
      p[a] = box.lo[a] + (0.15 + 0.7 * unit(rng)) * (box.hi[a] - box.lo[a]);
    return p;
  };
  for (int m = 0; m < moves; ++m) {
    const glm::dvec3 dir = randomUnit(rng);
    const double r = 0.6 + 0.6 * unit(rng);
    const bool ball = unit(rng) < 0.6;
    const glm::dvec3 p0 = inside(), p1 = inside();
    for (int i = 0; i < stampsPerMove; ++i) {
      const glm::dvec3 tip = p0 + (p1 - p0) * (double(i) / (stampsPerMove - 1));
      out.push_back({ball ? ballMill(tip, dir, r, 8.0) : flatMill(tip, dir, r, 8.0), dir, r});
    }
  }
  return out;
}

}  // namespace mdhd::mdh::testing

#pragma once
// The eleven examples of thesis section 6.1 recreated as stamped tool motions
// (the thesis shows pictures only; shapes and sizes here are our reading).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/geometry/line_solid.h"

namespace mdhd::mdh::bench {

struct Step {
  std::shared_ptr<geom::LineSolid> solid;
  glm::dvec3 direction;
  double radius;
};

struct ThesisCase {
  std::string name;
  geom::Aabb stock;
  std::vector<Step> steps;
};

// Stock 10 mm cube; `stampsPerMm` sets the in-between step density.
std::vector<ThesisCase> thesisCases(double stampsPerMm);

}  // namespace mdhd::mdh::bench

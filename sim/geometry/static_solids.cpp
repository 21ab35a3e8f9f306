#include "sim/geometry/static_solids.h"

#include <cmath>
#include <stdexcept>

namespace mdhd::geom {

namespace {

ToolPart cylinderPart(double radius, double height) {
  if (!(radius > 0.0) || !std::isfinite(radius) || !(height > 0.0) || !std::isfinite(height))
    throw std::invalid_argument("cylinder: radius and height must be > 0");
  ToolPart part;
  part.bodies.push_back(ConvexBody{{cylinderPiece(0.0, height, radius)}});
  return part;
}

}  // namespace

BoxSolid::BoxSolid(const glm::dvec3& lo, const glm::dvec3& hi) : box_{lo, hi} {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(lo[i]) || !std::isfinite(hi[i]))
      throw std::invalid_argument("box: corners must be finite");
    if (lo[i] > hi[i]) throw std::invalid_argument("box: min must be <= max on every axis");
  }
}

void BoxSolid::lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const {
  if (axis < 0 || axis > 2) return;
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  if (u < box_.lo[i1] || u > box_.hi[i1] || v < box_.lo[i2] || v > box_.hi[i2]) return;
  if (box_.hi[axis] > box_.lo[axis]) out.push_back(Interval{box_.lo[axis], box_.hi[axis]});
}

CylinderSolid::CylinderSolid(const glm::dvec3& base, const glm::dvec3& axis, double radius,
                             double height)
    : solid_(SweptVolume::at(cylinderPart(radius, height), ToolPose{base, axis})) {}

}  // namespace mdhd::geom

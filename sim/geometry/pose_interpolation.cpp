#include "sim/geometry/pose_interpolation.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace mdhd::geom {

namespace {
bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
}  // namespace

ToolPose normalizedPose(const ToolPose& pose) {
  if (!finite(pose.tip) || !finite(pose.axis))
    throw std::invalid_argument("tool pose: tip and axis must be finite");
  const double len2 = glm::dot(pose.axis, pose.axis);
  if (!(len2 > 1e-24)) throw std::invalid_argument("tool pose: axis must not be zero");
  // A unit axis stays as given, so the same pose always gives the same solid.
  if (std::abs(len2 - 1.0) <= 4.0 * std::numeric_limits<double>::epsilon()) return pose;
  return ToolPose{pose.tip, pose.axis / std::sqrt(len2)};
}

double axisAngle(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

ToolPose interpolatePose(const ToolPose& a, const ToolPose& b, double f) {
  ToolPose p;
  p.tip = a.tip + f * (b.tip - a.tip);
  const double th = axisAngle(a.axis, b.axis);
  if (th < 1e-9) {
    p.axis = glm::normalize(a.axis + f * (b.axis - a.axis));
  } else {
    const double s = std::sin(th);
    p.axis =
        glm::normalize((std::sin((1.0 - f) * th) / s) * a.axis + (std::sin(f * th) / s) * b.axis);
  }
  if (f == 0.0) p.axis = a.axis;  // the ends exactly, not up to rounding
  if (f == 1.0) p = b;
  return p;
}

}  // namespace mdhd::geom

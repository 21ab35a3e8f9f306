#pragma once
// Poses in between two poses: the tip on the segment, the axis on the great circle.
#include "sim/geometry/tool_pose.h"

namespace mdhd::geom {

// The pose with finite tip and a unit axis; throws std::invalid_argument for a
// non-finite value or a zero axis.
ToolPose normalizedPose(const ToolPose& pose);

// Angle between two unit axes, radians, accurate for small and large angles.
double axisAngle(const glm::dvec3& a, const glm::dvec3& b);

// The pose at fraction f in [0, 1] from a to b (unit axes, not opposite).
ToolPose interpolatePose(const ToolPose& a, const ToolPose& b, double f);

}  // namespace mdhd::geom

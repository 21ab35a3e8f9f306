#pragma once
// How far a point is from a tool part at a pose: what a caller needs to measure how
// deep a part reaches into material along the part's own geometry.
#include <glm/vec3.hpp>

#include "sim/geometry/tool_part.h"
#include "sim/geometry/tool_pose.h"

namespace mdhd::geom {

// Signed distance (mm) from `p` to one convex body in the tool frame: < 0 inside.
// Exact: a body of revolution's nearest point lies in the point's meridian plane.
double signedDistance(const ConvexBody& body, const glm::dvec3& p);

// Signed distance from `p` (in W) to the part at `pose`: the minimum over its bodies,
// exact outside and where the bodies do not overlap. +infinity for an empty part.
double signedDistance(const ToolPart& part, const ToolPose& pose, const glm::dvec3& p);

}  // namespace mdhd::geom

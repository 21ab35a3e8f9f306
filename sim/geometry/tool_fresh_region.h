#pragma once
// The fresh region (fresh_region.h) of a tool part translated between two poses.
#include <optional>

#include "sim/geometry/fresh_region.h"
#include "sim/geometry/tool_part.h"
#include "sim/geometry/tool_pose.h"

namespace mdhd::geom {

// The region for the part moving from `a` to `b` with its axis held, or nothing
// when the axis turns (the sweep is then not exactly T(a) + segment) or the part
// is empty.
std::optional<FreshRegion> freshRegion(const ToolPart& part, const ToolPose& a, const ToolPose& b);

}  // namespace mdhd::geom

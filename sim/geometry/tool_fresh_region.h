#pragma once
// The fresh region (fresh_region.h) of a tool part translated between two poses.
#include <optional>
#include <span>

#include <glm/vec3.hpp>

#include "sim/geometry/fresh_region.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_part.h"
#include "sim/geometry/tool_pose.h"

namespace mdhd::geom {

// The region for the part moving from `a` to `b` with its axis held, or nothing
// when the axis turns (the sweep is then not exactly T(a) + segment) or the part
// is empty.
std::optional<FreshRegion> freshRegion(const ToolPart& part, const ToolPose& a, const ToolPose& b);

// Appends to `region` a superset of T(to) \ T(from), T(w) the part with axis w turned
// about `pivot`, the point at `pivotHeight` on its axis (from and to unit, not opposite).
//
// Why it holds: a point x of T(to) outside T(from), followed back along the turn in
// the part's frame, enters the part through a boundary point y where the turn's
// velocity v = k x (y - pivot) leaves through the outward normal n (n . v >= 0), and
// x is where y is at some angle of the turn. With u = k x w (where the axis's upper
// end goes), y at height z above the pivot, radius r(z) in radial direction e:
// n . v has the sign of (u . e)(z + r r'(z)) on a side, of u . e on a bottom face and
// of -(u . e) on a top face. So each stretch of a side where z + r r' keeps its sign
// (a ball zone: the sign of its centre's height; a frustum: linear in z, split where
// it changes) contributes one half of its points, (x - pivot) . u of one sign, taken
// over the turn: the box of the stretch at both ends of the turn grown by the arc's
// sagitta, and the half-space at the middle axis loosened by what the turn moves it.
void addTurnRegion(const ToolPart& part, double pivotHeight, const glm::dvec3& pivot,
                   const glm::dvec3& from, const glm::dvec3& to, FreshRegion& region);

// The fresh region of a cut of `moves` (SweptVolume::translations(), each holding its
// axis), the part standing at `held` before it (where the last cut left it): the
// union of each translation's region (freshRegion) and of the turns between held
// poses (from `held` to the first start, from each end to the next start), which
// SweptVolume::between makes about the point at part.turnPivot() on the axis.
// Nothing when two consecutive held poses do not share that point (within 1e-9 mm,
// the interpolation's rounding): they are then no turn about it.
std::optional<FreshRegion> freshRegion(const ToolPart& part, const ToolPose& held,
                                       std::span<const Translation> moves);

}  // namespace mdhd::geom

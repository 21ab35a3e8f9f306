#pragma once
// Where a swept piece of a tool can lie inside a box: a tighter bound than its own
// box wherever the piece leans (a tilted shank's box holds its whole length; the part
// of it inside a brick a few millimetres tall is much narrower).
#include <glm/vec3.hpp>

#include "sim/geometry/line_solid.h"

namespace mdhd::geom {

// The solid of disks of radius <= `radius` square to the unit vector `axis`, centred
// on the parallelogram {tip + t * move + s * axis : t in [0, 1], s in [z0, z1]} (a
// piece of revolution of a tool translated by `move`), intersected with `box`: a box
// that holds it (lo > hi on some axis when it misses). A disk's extent along axis k
// is radius * sqrt(1 - axis[k]^2), so a point of the solid in `box` has its centre
// in `box` grown by that much: the parallelogram is clipped to that grown box and
// its bounds grown back.
Aabb sweptPieceBoundsIn(const glm::dvec3& tip, const glm::dvec3& move, const glm::dvec3& axis,
                        double z0, double z1, double radius, const Aabb& box);

}  // namespace mdhd::geom

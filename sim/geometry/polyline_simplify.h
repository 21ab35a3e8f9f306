#pragma once
// Which points a chain of tool tips (a chain of translations) can do without while
// every point dropped stays within `tolerance` of the segment that replaces it. Each
// kept point's chord reaches as far along the chain as it can (Douglas-Peucker, used
// before, halves a chain: on an arc whose chords fit three steps but not four, chains
// of 2^k steps fell to chords of two).
//
// Why that is enough: a segment of the chain has both its ends within `tolerance` of
// the chord, so it lies within `tolerance` of it (the distance to a segment is
// convex), and the chord within `tolerance` of the chain (the chain's projection onto
// it covers it): the two paths are within `tolerance` of each other both ways, and so
// are the swept volumes of one tool shape translated along them.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace mdhd::geom {

// Indices of the points kept, ascending: the first and the last, every point marked
// in `fixed` (same size as `points`, or empty for none), and the ends of the longest
// chords, taken from the start, that keep the others within `tolerance` (>= 0; 0
// drops only points on the segment exactly).
void simplifyPolyline(std::span<const glm::dvec3> points, std::span<const std::uint8_t> fixed,
                      double tolerance, std::vector<std::size_t>& kept);

}  // namespace mdhd::geom

#pragma once
// Triangles for one closed polygon of the mesh (a cube's line loop or the
// solid part of a boundary square).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace mdhd::mesh {

// Cross products shorter than this (grid units^2) count as degenerate.
inline constexpr double kMinDoubleArea = 1e-9;

// Triangulates the polygon p (counter-clockwise seen from where its normal
// points) as a fan from the vertex that gives the best-shaped triangles. A
// diagonal (i, j) is only used when masks[i] & masks[j] == 0: two crossings on
// one face of the cube must not be joined through the cube, or the neighbour
// across that face could use the same edge too. When no fan qualifies, a
// centre vertex is added (index p.size() in `out`, position in `centre`).
// Returns false when the centre was needed.
bool triangulateLoop(std::span<const glm::dvec3> p, std::span<const std::uint8_t> masks,
                     std::vector<std::array<int, 3>>& out, glm::dvec3& centre);

}  // namespace mdhd::mesh

#pragma once
// How deep material reaches into a swept tool part, estimated on grid lines:
// along z lines through the sampling grid's vertices (every `stride`-th where
// the part is wide), the material's intervals are intersected with the sweep's,
// and points of each overlap are measured against the part: depth = how far the
// point lies inside the part at the pose along the sweep where it lies deepest.
#include <functional>
#include <limits>
#include <vector>

#include "sim/geometry/line_solid.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_part.h"

namespace mdhd::check {

// Material along the z line at vertex (ix, iy) of the grid, which sits at (x, y) mm.
using MaterialLine =
    std::function<void(int ix, int iy, double x, double y, std::vector<geom::Interval>& out)>;

// The grid the lines run on: vertex (ix, iy) is at origin + (ix, iy) * h.
struct LineGrid {
  double origin_x = 0.0;
  double origin_y = 0.0;
  double h = 0.1;
  int ix_min = 0, ix_max = -1;  // vertex range that may be sampled (inclusive)
  int iy_min = 0, iy_max = -1;
};

// At most this many lines per axis: wider parts are sampled every few lines.
inline constexpr int kMaxDepthLinesPerAxis = 64;
inline constexpr int kMaxDepthSamplesPerOverlap = 16;

struct Penetration {
  double depth = 0.0;        // mm, deepest point found (0: none)
  glm::dvec3 deepest{0.0};   // where
  double max_overlap = 0.0;  // mm, longest overlap along one line
};

// `within`: only this box of the part's bounds is sampled (e.g. its overlap with a
// fixture); lines outside `grid` are skipped. `measure` false: only max_overlap.
// Overlaps are sampled in the order of a bound on their depth (half the sweep's own
// interval on the line) and skipped once that bound cannot beat the depth found by more
// than h/4 (the result is within h/4 of sampling them all). `enough`: stops at the first sample deeper
// than that (a lower bound of the depth).
Penetration penetration(const geom::SweptVolume& sweep, const geom::ToolPart& part,
                        const geom::Aabb& within, const LineGrid& grid,
                        const MaterialLine& material, bool measure = true,
                        double enough = std::numeric_limits<double>::infinity());

// Signed distance from p to the part swept along the sweep: min over its translations
// of the min over the translation of the part's distance (each convex body's is
// convex along a translation, so a golden-section search finds it).
double sweptSignedDistance(const geom::SweptVolume& sweep, const geom::ToolPart& part,
                           const glm::dvec3& p);

// Box intersection (may come out inverted: check with isEmpty).
geom::Aabb intersect(const geom::Aabb& a, const geom::Aabb& b);
bool isEmpty(const geom::Aabb& b);

}  // namespace mdhd::check

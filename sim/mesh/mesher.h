#pragma once
// The triangle mesh of an mdh-map (thesis chapter 4): per grid cube the
// marching-cubes loops of the 3-map (interior mesh, 4.3.2), per square of the
// stock's boundary box its solid polygon (exterior mesh, 4.3.1). Every vertex
// and edge crossing is read from one owner leaf (stock_view.h), so the mesh
// is closed across cells of any directions, in one pass over the leaves.
#include <cstdint>
#include <optional>

#include "sim/geometry/line_solid.h"
#include "sim/mesh/mesh_sink.h"

namespace mdhd::mdh {
class Stock;
}

namespace mdhd::mesh {

class StockView;

// Crossings are kept this far (grid units) from the edge's ends, so no
// triangle collapses where the surface passes through a grid vertex.
inline constexpr double kCrossingMargin = 1e-3;
// ... and at least this many float32 steps at the stock's farthest coordinate
// from W's origin. STL stores vertices as float32, whose step is 6.1e-5 mm from
// 512 mm on (3.1e-5 from 256, 1.5e-5 from 128): more than 1e-3 grid units at
// density 20 from 512 mm, at density 50 from 256, at 100 from 128. Crossings
// that close to their grid vertex were written onto it or beside it (zero-area
// triangles, edges of four triangles, facet normals off by up to 45 degrees).
inline constexpr double kCrossingFloatSteps = 8.0;
// The margin the mesher keeps for this view (grid units): kCrossingMargin, or
// kCrossingFloatSteps float32 steps if larger (at most 0.25): at density 10
// larger from 128 mm (1.2e-3), at density 50 from 32 mm.
double crossingMargin(const StockView& view);

struct MeshOptions {
  // Only the cells overlapping this box (mm, W), for viewers. The result is
  // then open where the region cuts through material.
  std::optional<geom::Aabb> region;
  // Threads meshing runs of leaves, the calling thread one of them; the sink
  // still gets every triangle from the calling thread, in the same order and
  // with the same keys as with one.
  int threads = 1;
  // With threads > 1, what bounds the triangles held at once: runs of at most
  // about `runWork` (estimated surface cubes and boundary squares, roughly
  // triangles), of which `runsPerThread` per thread are meshed or buffered at
  // a time. Tests shrink them; the output does not depend on them.
  std::int64_t runWork = 2048;
  int runsPerThread = 2;
};

struct MeshStats {
  std::int64_t triangles = 0;
  std::int64_t exteriorTriangles = 0;  // on the stock's boundary box
  std::int64_t surfaceCubes = 0;       // cubes with a loop
  std::int64_t loops = 0;
  std::int64_t centreVertices = 0;     // loops that needed an added vertex
  std::int64_t fallbackCrossings = 0;  // edges whose owner had no crossing (engine disagreement)
  std::int64_t degenerateTriangles = 0;
  int leaves = 0;        // leaves meshed
  int brokenLeaves = 0;  // see StockView::brokenLeaves
};

// Streams the mesh into `sink`. Throws std::invalid_argument for a region
// whose min exceeds its max or holds a NaN.
MeshStats meshStock(const mdh::Stock& stock, MeshSink& sink, const MeshOptions& options = {});
MeshStats meshStock(const StockView& view, MeshSink& sink, const MeshOptions& options = {});

}  // namespace mdhd::mesh

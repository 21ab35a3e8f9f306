#pragma once
// Meshing on several threads with the output of one: the leaves are cut into
// runs, workers mesh runs into buffers, and the calling thread hands the
// buffers to the sink in run order, numbering the added (kInner) vertices on
// as one mesher would. At most a few runs per thread are buffered at a time.
#include <functional>
#include <span>
#include <vector>

#include "sim/mesh/mesh_sink.h"
#include "sim/mesh/mesher.h"

namespace mdhd::mesh {

// Meshes `leaves` (in order) into `out`, counting into `stats`.
using MeshRun = std::function<void(std::span<const int> leaves, MeshSink& out, MeshStats& stats)>;

// Adds every run's statistics to `stats`. An exception from a run or from the
// sink stops the workers and is rethrown here.
void meshInParallel(const std::vector<int>& leaves, int threads, MeshSink& sink, MeshStats& stats,
                    const MeshRun& run);

}  // namespace mdhd::mesh

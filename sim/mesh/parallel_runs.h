#pragma once
// Meshing on several threads with the output of one: the leaves are cut into
// runs of about equal estimated work, workers mesh runs ahead into buffers,
// and the calling thread hands the buffers to the sink in run order, numbering
// the added (kInner) vertices on as one mesher would. The calling thread
// meshes too: the run due next straight into the sink when no worker has
// taken it. Memory stays small whatever the mesh's size: runs are short, only
// a window of them is meshed or buffered at a time, and buffers are reused.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "sim/mesh/mesh_sink.h"
#include "sim/mesh/mesher.h"

namespace mdhd::mesh {

// Meshes `leaves` (in order) into `out`, counting into `stats`.
using MeshRun = std::function<void(std::span<const int> leaves, MeshSink& out, MeshStats& stats)>;

// Where runs end: run r is [ends[r-1], ends[r]) of the leaves (ends[-1] = 0).
// A run closes once it holds `maxWork` (the leaves' work estimates summed), or
// earlier so that there are at least `minRuns` (load balance); a leaf is never
// split.
std::vector<std::size_t> cutRuns(std::span<const std::int64_t> work, std::int64_t maxWork,
                                 std::size_t minRuns);

struct ParallelRuns {
  std::vector<std::size_t> ends;  // from cutRuns
  int threads = 2;                // meshing threads, the calling thread one of them
  int window = 4;                 // runs started and not yet at the sink (>= 1)
};

// Adds every run's statistics to `stats`. An exception from a run or from the
// sink stops the workers and is rethrown here.
void meshInParallel(std::span<const int> leaves, const ParallelRuns& runs, MeshSink& sink,
                    MeshStats& stats, const MeshRun& run);

}  // namespace mdhd::mesh

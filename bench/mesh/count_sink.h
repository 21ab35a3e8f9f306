#pragma once
// A mesh sink that only counts triangles: meshing throughput without the cost of
// keeping or writing the mesh.
#include <cstdint>

#include "sim/mesh/mesher.h"

namespace mdhd::mesh::bench {

class CountSink final : public MeshSink {
 public:
  void triangle(const MeshVertex&, const MeshVertex&, const MeshVertex&, bool) override {
    ++triangles;
  }
  std::int64_t triangles = 0;
};

}  // namespace mdhd::mesh::bench

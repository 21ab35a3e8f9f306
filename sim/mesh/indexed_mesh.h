#pragma once
// A mesh with shared vertices, collected from the mesher, and the checks that
// say it is a closed, consistently oriented 2-manifold.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/mesh/mesh_sink.h"

namespace mdhd::mesh {

class IndexedMesh final : public MeshSink {
 public:
  void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                bool exterior) override;

  const std::vector<glm::dvec3>& positions() const { return positions_; }
  const std::vector<std::array<std::uint32_t, 3>>& triangles() const { return triangles_; }
  bool exterior(std::size_t triangle) const { return exterior_[triangle] != 0; }
  std::size_t memoryBytes() const;

 private:
  std::uint32_t index(const MeshVertex& v);

  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> index_;
  std::vector<glm::dvec3> positions_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
  std::vector<std::uint8_t> exterior_;
};

struct EdgeReport {
  std::int64_t edges = 0;
  std::int64_t open = 0;           // used by one triangle only
  std::int64_t overused = 0;       // used by more than two
  std::int64_t sameDirection = 0;  // two uses running the same way (flipped orientation)
  std::int64_t collapsed = 0;      // triangles using one vertex twice
  bool closed() const { return open == 0 && overused == 0 && sameDirection == 0 && collapsed == 0; }
};

// Every edge must be used by exactly two triangles, once in each direction.
EdgeReport checkEdges(const IndexedMesh& mesh);
// Vertices whose triangles do not form one fan closing on itself.
std::int64_t nonManifoldVertices(const IndexedMesh& mesh);
// Signed volume (mm^3) by the divergence theorem: positive when normals point out.
double enclosedVolume(const IndexedMesh& mesh);
double surfaceArea(const IndexedMesh& mesh);
double smallestTriangleArea(const IndexedMesh& mesh);

}  // namespace mdhd::mesh

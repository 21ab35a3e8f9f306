#pragma once
// Where the mesher puts its triangles. A triangle comes with its three
// vertices' identities, so a consumer can share vertices (and check that the
// mesh is closed) without comparing coordinates, or ignore them and stream.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace mdhd::mesh {

// What a vertex stands for: a grid vertex (a solid corner on the stock's
// boundary), the surface crossing on a grid edge, or a point added inside one
// cube's polygon. Grid coordinates are packed 21 bits each.
enum class VertexKind : std::uint8_t { kEdgeX, kEdgeY, kEdgeZ, kCorner, kInner };

struct VertexKey {
  std::uint64_t where = 0;  // packed grid vertex (edge start), or a serial number for kInner
  VertexKind kind = VertexKind::kCorner;
  bool operator==(const VertexKey&) const = default;
};

inline std::uint64_t packGridVertex(int x, int y, int z) {
  return std::uint64_t(std::uint32_t(x)) | (std::uint64_t(std::uint32_t(y)) << 21) |
         (std::uint64_t(std::uint32_t(z)) << 42);
}

struct VertexKeyHash {
  std::size_t operator()(const VertexKey& k) const {
    std::uint64_t h = k.where * 0x9e3779b97f4a7c15ULL + std::uint64_t(k.kind);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

struct MeshVertex {
  glm::dvec3 position{0.0};  // mm in the workpiece frame W
  VertexKey key;
};

// Triangles arrive counter-clockwise seen from outside the material (the
// right-hand normal points out). `exterior`: the triangle lies on the stock's
// original boundary box, not on a machined surface.
class MeshSink {
 public:
  virtual ~MeshSink() = default;
  virtual void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                        bool exterior) = 0;
};

// A sink that keeps every triangle, in order (parallel meshing buffers runs in
// them; tests compare meshes with them).
struct BufferedTriangle {
  MeshVertex v[3];
  bool exterior = false;
};

class TriangleBuffer final : public MeshSink {
 public:
  void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                bool exterior) override {
    tris.push_back({{a, b, c}, exterior});
  }
  std::vector<BufferedTriangle> tris;
};

}  // namespace mdhd::mesh

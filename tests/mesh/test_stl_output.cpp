// A machined stock streamed to binary STL and read back: the same triangles,
// outward normals, the same enclosed volume.
#include <cstring>
#include <sstream>

#include <gtest/gtest.h>

#include "protocol/stl.h"
#include "tests/mesh/mesh_test_support.h"

namespace mdhd::mesh {
namespace {

struct StlTriangle {
  glm::dvec3 n, a, b, c;
};

std::vector<StlTriangle> readStl(const std::string& s) {
  auto f32 = [&](std::size_t at) {
    float f;
    std::memcpy(&f, s.data() + at, 4);  // the test machine is little-endian like the format
    return double(f);
  };
  std::uint32_t count;
  std::memcpy(&count, s.data() + 80, 4);
  EXPECT_EQ(s.size(), 84 + 50 * std::size_t(count));
  std::vector<StlTriangle> out(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::size_t r = 84 + 50 * std::size_t(i);
    glm::dvec3 v[4];
    for (int k = 0; k < 4; ++k) v[k] = {f32(r + 12 * k), f32(r + 12 * k + 4), f32(r + 12 * k + 8)};
    out[i] = {v[0], v[1], v[2], v[3]};
  }
  return out;
}

TEST(StlOutput, MachinedStockRoundTrips) {
  mdh::Stock stock({{-2, 1, 0}, {2, 4, 2}}, testing::stockOptions(10));
  stock.cut(testing::Ball({0, 2.5, 2}, 1.2), {0, 0, 1});
  const geom::ToolPart part = testing::toolPart(geom::ToolShape::kFlat, 1.0);
  const glm::dvec3 side(1, 0, 0);
  stock.setToolRadius(0.5);
  stock.cut(
      geom::SweptVolume::between(part, {{1.0, 2.5, 0.8}, side}, {{1.0, 1.8, 0.8}, side}, 0, 0.01),
      side);
  IndexedMesh mesh;
  std::stringstream out;
  protocol::StlWriter stl(out, "machined stock");
  struct Both final : MeshSink {
    MeshSink& x;
    MeshSink& y;
    Both(MeshSink& a, MeshSink& b) : x(a), y(b) {}
    void triangle(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c, bool e) override {
      x.triangle(a, b, c, e);
      y.triangle(a, b, c, e);
    }
  } both(mesh, stl);
  const MeshStats stats = meshStock(stock, both);
  stl.finish();
  EXPECT_EQ(stl.written(), static_cast<std::uint64_t>(stats.triangles));

  const std::vector<StlTriangle> tris = readStl(out.str());
  ASSERT_EQ(tris.size(), mesh.triangles().size());
  double volume = 0.0;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const StlTriangle& t = tris[i];
    const auto& ref = mesh.triangles()[i];
    EXPECT_NEAR(glm::length(t.a - mesh.positions()[ref[0]]), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(t.c - mesh.positions()[ref[2]]), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(t.n), 1.0, 1e-6);
    // The stored normal is the right-hand normal of the stored vertices.
    const glm::dvec3 rh = glm::cross(t.b - t.a, t.c - t.a);
    if (glm::length(rh) > 1e-9) {
      EXPECT_GT(glm::dot(glm::normalize(rh), t.n), 0.99);
    }
    volume += glm::dot(t.a, glm::cross(t.b, t.c)) / 6.0;
  }
  EXPECT_NEAR(volume, enclosedVolume(mesh), 1e-4);
  EXPECT_NEAR(volume, stock.volume(), 0.02 * surfaceArea(mesh) * 0.1);
  EXPECT_LT(volume, 4 * 3 * 2 - 1.0);  // both cuts removed material
}

}  // namespace
}  // namespace mdhd::mesh

// A machined stock streamed to binary STL and read back: the same triangles,
// outward normals, the same enclosed volume.
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "protocol/stl.h"
#include "sim/mesh/stock_view.h"
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

// What a tool that loads the file sees: vertices are welded by their float
// coordinates, so two vertices the mesher keeps apart must stay apart in float32.
struct WeldedStl {
  int zeroArea = 0;    // triangles whose stored vertices are collinear
  int normalsOff = 0;  // stored normal more than 8 degrees from the stored winding's
  int badEdges = 0;    // edges not in exactly one triangle each way
  double volume = 0.0;
};

WeldedStl weld(const std::vector<StlTriangle>& tris) {
  WeldedStl w;
  using Key = std::array<double, 3>;
  std::map<Key, int> index;
  auto id = [&](const glm::dvec3& p) {
    return index.emplace(Key{p.x, p.y, p.z}, static_cast<int>(index.size())).first->second;
  };
  std::map<std::pair<int, int>, int> edges;  // directed edge -> uses
  for (const StlTriangle& t : tris) {
    const glm::dvec3 rh = glm::cross(t.b - t.a, t.c - t.a);
    if (glm::length(rh) == 0.0)
      ++w.zeroArea;
    else if (glm::dot(glm::normalize(rh), t.n) < std::cos(8.0 * testing::kPi / 180.0))
      ++w.normalsOff;
    const int v[3] = {id(t.a), id(t.b), id(t.c)};
    for (int k = 0; k < 3; ++k) ++edges[{v[k], v[(k + 1) % 3]}];
    w.volume += glm::dot(t.a, glm::cross(t.b, t.c)) / 6.0;
  }
  for (const auto& [e, uses] : edges) {
    const auto back = edges.find({e.second, e.first});
    if (uses != 1 || back == edges.end() || back->second != 1) ++w.badEdges;
  }
  return w;
}

// A hemisphere pocket whose sphere passes through many grid vertices (radius 25
// grid spacings: 25^2 is a sum of squares in many ways), so many crossings sit at
// the margin from their vertex. Far from W's origin float32 cannot hold 1e-3 grid
// units there: with that margin alone the file at 300 mm had 96 zero-area triangles,
// 160 normals more than 8 degrees off the winding and 216 edges not shared by one
// triangle each way (1000 mm: 104, 176, 260). Near the origin it was fine.
TEST(StlOutput, FarFromTheOriginTheFileStaysClosed) {
  for (const double at : {0.0, 300.0, 1000.0}) {
    SCOPED_TRACE(at);
    const double density = 50.0, r = 0.5;
    mdh::Stock stock({{at, at, -1}, {at + 2, at + 2, 0}}, testing::stockOptions(density));
    stock.cut(testing::Ball({at + 1, at + 1, 0}, r), {0, 0, 1});
    std::stringstream out;
    protocol::StlWriter stl(out, "far stock");
    const MeshStats stats = meshStock(stock, stl);
    stl.finish();
    EXPECT_EQ(stats.degenerateTriangles, 0);
    const std::vector<StlTriangle> tris = readStl(out.str());
    ASSERT_GT(tris.size(), 1000u);
    const WeldedStl w = weld(tris);
    EXPECT_EQ(w.zeroArea, 0);
    EXPECT_EQ(w.normalsOff, 0);
    EXPECT_EQ(w.badEdges, 0);
    // The box less the hemisphere, within the discretisation (crossings are exact
    // on the sphere; the margin is at most 8 float steps, 4.9e-4 mm here).
    const double expected = 4.0 - 2.0 / 3.0 * testing::kPi * r * r * r;
    EXPECT_NEAR(w.volume, expected, 5e-3);
  }
}

// The margin is 1e-3 grid units near W's origin and grows with the float32 step
// of the farthest coordinate, never beyond a quarter of the spacing.
TEST(StlOutput, CrossingMarginFollowsFloatSteps) {
  const auto margin = [](double at, double density) {
    mdh::Stock stock({{at, 0, -1}, {at + 1, 1, 0}}, testing::stockOptions(density));
    return crossingMargin(StockView(stock));
  };
  EXPECT_EQ(margin(0.0, 10.0), kCrossingMargin);
  EXPECT_EQ(margin(99.0, 5.0), kCrossingMargin);  // the 3-axis examples' scale
  // 1000 mm: float32 step 2^-14 mm; 8 of them at density 50 (0.02 mm).
  EXPECT_DOUBLE_EQ(margin(999.0, 50.0), 8.0 * std::ldexp(1.0, -14) * 50.0);
  EXPECT_EQ(margin(1e6, 100.0), 0.25);
}

}  // namespace
}  // namespace mdhd::mesh

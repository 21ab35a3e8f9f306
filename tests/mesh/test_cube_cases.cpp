// The generated marching-cubes cases: tables, loops for every corner pattern,
// the ambiguous-face rule, and closedness of a mesh assembled from cubes over
// arbitrary (not heightmap-shaped) corner patterns.
#include "sim/mesh/cube_cases.h"

#include <bit>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sim/mesh/indexed_mesh.h"
#include "sim/mesh/loop_triangulation.h"
#include "sim/mesh/mesher.h"

namespace mdhd::mesh {
namespace {

glm::dvec3 cornerOffset(int c) {
  return {double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
}

TEST(CubeCases, FacesRunCounterClockwiseSeenFromOutside) {
  int edgeUses[12] = {};
  for (const CubeFace& f : cubeFaces()) {
    glm::dvec3 outward(0.0);
    outward[f.axis] = f.side == 0 ? -1.0 : 1.0;
    const glm::dvec3 p0 = cornerOffset(f.corners[0]), p1 = cornerOffset(f.corners[1]),
                     p2 = cornerOffset(f.corners[2]);
    EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), outward), 0.0);
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(cornerOffset(f.corners[i])[f.axis], double(f.side));
      const CubeEdge& e = cubeEdges()[f.edges[i]];
      const std::set<int> ends{e.from, e.to}, want{f.corners[i], f.corners[(i + 1) % 4]};
      EXPECT_EQ(ends, want);
      ++edgeUses[f.edges[i]];
    }
    // The frame edges: u0 u1 along u, v0 v1 along v.
    EXPECT_EQ(cubeEdges()[f.frameEdges[0]].axis, (f.axis + 1) % 3);
    EXPECT_EQ(cubeEdges()[f.frameEdges[1]].axis, (f.axis + 1) % 3);
    EXPECT_EQ(cubeEdges()[f.frameEdges[2]].axis, (f.axis + 2) % 3);
    EXPECT_EQ(cubeEdges()[f.frameEdges[3]].axis, (f.axis + 2) % 3);
  }
  for (int e = 0; e < 12; ++e) {
    EXPECT_EQ(edgeUses[e], 2) << e;
    EXPECT_EQ(std::popcount(edgeFaces(e)), 2) << e;
    const CubeEdge& ce = cubeEdges()[e];
    EXPECT_EQ(ce.to - ce.from, 1 << ce.axis);
  }
}

TEST(CubeCases, EveryPatternGivesLoopsThroughEachCrossingOnce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.05, 0.95);
  for (unsigned mask = 0; mask < 256; ++mask) {
    for (int trial = 0; trial < 4; ++trial) {
      double t[12];
      for (double& x : t) x = unit(rng);
      const CubeLoops loops = cubeLoops(mask, t);
      int crossing = 0;
      for (const CubeEdge& e : cubeEdges())
        crossing += ((mask >> e.from) & 1u) != ((mask >> e.to) & 1u);
      int total = 0;
      for (int l = 0; l < loops.count; ++l) {
        EXPECT_GE(loops.size[l], 3) << mask;
        total += loops.size[l];
      }
      ASSERT_EQ(total, crossing) << mask;
      std::set<int> seen(loops.edges.begin(), loops.edges.begin() + total);
      EXPECT_EQ(static_cast<int>(seen.size()), total) << mask;
      for (int e : seen) {
        const CubeEdge& ce = cubeEdges()[e];
        EXPECT_NE((mask >> ce.from) & 1u, (mask >> ce.to) & 1u) << mask;
      }
      // Consecutive loop points share a face (the segment lies on it).
      int at = 0;
      for (int l = 0; l < loops.count; ++l) {
        for (int k = 0; k < loops.size[l]; ++k) {
          const int a = loops.edges[at + k], b = loops.edges[at + (k + 1) % loops.size[l]];
          EXPECT_NE(edgeFaces(a) & edgeFaces(b), 0u) << mask;
        }
        at += loops.size[l];
      }
    }
  }
}

TEST(CubeCases, TheTableGivesWhatTheFacesGive) {
  // Unambiguous patterns come from a table built once; it must hold what reading
  // the faces gives for any crossings. Ambiguous ones are read each time.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.02, 0.98);
  int ambiguous = 0;
  for (unsigned mask = 0; mask < 256; ++mask) {
    ambiguous += hasAmbiguousFace(mask);
    for (int trial = 0; trial < 8; ++trial) {
      double t[12];
      for (double& x : t) x = unit(rng);
      const CubeLoops a = cubeLoops(mask, t), b = cubeLoopsRead(mask, t);
      ASSERT_EQ(a.count, b.count) << mask;
      EXPECT_EQ(a.size, b.size) << mask;
      EXPECT_EQ(a.edges, b.edges) << mask;
    }
  }
  // The same count from corner coordinates: a face (axis, side) is ambiguous when
  // its solid corners are exactly one diagonal.
  int expected = 0;
  for (unsigned mask = 0; mask < 256; ++mask) {
    bool any = false;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        auto in = [&](int cu, int cv) {
          const int c = (side << axis) | (cu << u) | (cv << v);
          return ((mask >> c) & 1u) != 0;
        };
        any = any || (in(0, 0) == in(1, 1) && in(1, 0) == in(0, 1) && in(0, 0) != in(1, 0));
      }
    expected += any;
  }
  EXPECT_EQ(ambiguous, expected);
  EXPECT_GT(ambiguous, 0);
}

TEST(CubeCases, LoneSolidCornerIsCutOffWithOutwardNormal) {
  double t[12];
  for (double& x : t) x = 0.5;
  const CubeLoops loops = cubeLoops(1u, t);  // only corner 0 solid
  ASSERT_EQ(loops.count, 1);
  ASSERT_EQ(loops.size[0], 3);
  glm::dvec3 p[3];
  for (int k = 0; k < 3; ++k) {
    const CubeEdge& e = cubeEdges()[loops.edges[k]];
    p[k] = cornerOffset(e.from);
    p[k][e.axis] += 0.5;
  }
  const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
  EXPECT_GT(glm::dot(n, glm::dvec3(1, 1, 1)), 0.0);  // away from the solid corner
  // The complement: the normal turns round.
  const CubeLoops inverse = cubeLoops(0xfeu, t);
  ASSERT_EQ(inverse.count, 1);
  glm::dvec3 q[3];
  for (int k = 0; k < 3; ++k) {
    const CubeEdge& e = cubeEdges()[inverse.edges[k]];
    q[k] = cornerOffset(e.from);
    q[k][e.axis] += 0.5;
  }
  EXPECT_LT(glm::dot(glm::cross(q[1] - q[0], q[2] - q[0]), glm::dvec3(1, 1, 1)), 0.0);
}

TEST(CubeCases, AmbiguousFaceTakesTheShorterSeparation) {
  // q00 and q11 solid. Crossings near the solid corners: a groove along the
  // empty diagonal, the solid corners stay apart.
  EXPECT_FALSE(solidJoined(true, 0.1, 0.9, 0.1, 0.9));
  // Crossings near the empty corners: a ridge along the solid diagonal.
  EXPECT_TRUE(solidJoined(true, 0.9, 0.1, 0.9, 0.1));
  // The other diagonal solid: mirrored.
  EXPECT_TRUE(solidJoined(false, 0.1, 0.9, 0.1, 0.9));
  EXPECT_FALSE(solidJoined(false, 0.9, 0.1, 0.9, 0.1));
  // A tie (the saddle's centre) joins, as the thesis's single interpretation.
  EXPECT_TRUE(solidJoined(true, 0.5, 0.5, 0.5, 0.5));
  EXPECT_TRUE(solidJoined(false, 0.5, 0.5, 0.5, 0.5));
}

TEST(CubeCases, AmbiguousFaceSegments) {
  const CubeFace& f = cubeFaces()[5];  // z = 1, corners 4 5 7 6 counter-clockwise
  double t[12];
  for (double& x : t) x = 0.5;
  const unsigned solid = (1u << 4) | (1u << 7);  // q00 and q11
  std::array<std::pair<int, int>, 2> segs;
  ASSERT_EQ(faceSegments(f, solid, t, segs), 2);  // the tie: joined, empty corners cut off
  for (int i = 0; i < 2; ++i) {
    const CubeEdge& in = cubeEdges()[segs[i].first];
    const CubeEdge& out = cubeEdges()[segs[i].second];
    // Each segment cuts off one empty corner (5 or 6): both edges touch it.
    const int corner = (in.from == out.from || in.from == out.to) ? in.from : in.to;
    EXPECT_TRUE(corner == 5 || corner == 6) << corner;
  }
}

// Builds the closed surface of an arbitrary solid pattern on an n^3 vertex
// grid (empty on its boundary, random crossings) the way the mesher does:
// loops per cube, triangulated, vertices keyed by grid edge.
IndexedMesh assemble(int n, const std::vector<char>& solid, const std::vector<double>& tOfEdge,
                     MeshStats& stats) {
  auto at = [&](int x, int y, int z) { return solid[(z * n + y) * n + x] != 0; };
  auto edgeT = [&](int x, int y, int z, int axis) {
    return tOfEdge[((z * n + y) * n + x) * 3 + axis];
  };
  IndexedMesh mesh;
  std::vector<std::array<int, 3>> tris;
  std::uint64_t inner = 0;
  for (int z = 0; z + 1 < n; ++z)
    for (int y = 0; y + 1 < n; ++y)
      for (int x = 0; x + 1 < n; ++x) {
        unsigned mask = 0;
        for (int c = 0; c < 8; ++c)
          if (at(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1))) mask |= 1u << c;
        if (mask == 0 || mask == 255) continue;
        double t[12];
        for (int e = 0; e < 12; ++e) {
          const CubeEdge& ce = cubeEdges()[e];
          t[e] =
              edgeT(x + (ce.from & 1), y + ((ce.from >> 1) & 1), z + ((ce.from >> 2) & 1), ce.axis);
        }
        const CubeLoops loops = cubeLoops(mask, t);
        int first = 0;
        for (int l = 0; l < loops.count; ++l) {
          std::vector<glm::dvec3> pts;
          std::vector<std::uint8_t> masks;
          std::vector<MeshVertex> verts;
          for (int k = 0; k < loops.size[l]; ++k) {
            const CubeEdge& ce = cubeEdges()[loops.edges[first + k]];
            const int px = x + (ce.from & 1), py = y + ((ce.from >> 1) & 1),
                      pz = z + ((ce.from >> 2) & 1);
            glm::dvec3 g(px, py, pz);
            g[ce.axis] += t[loops.edges[first + k]];
            pts.push_back(g);
            masks.push_back(static_cast<std::uint8_t>(edgeFaces(loops.edges[first + k])));
            verts.push_back({g, {packGridVertex(px, py, pz), static_cast<VertexKind>(ce.axis)}});
          }
          tris.clear();
          glm::dvec3 centre;
          if (!triangulateLoop(pts, masks, tris, centre)) {
            verts.push_back({centre, {inner++, VertexKind::kInner}});
            ++stats.centreVertices;
          }
          for (const auto& tr : tris) {
            if (glm::length(glm::cross(verts[tr[1]].position - verts[tr[0]].position,
                                       verts[tr[2]].position - verts[tr[0]].position)) <=
                kMinDoubleArea)
              ++stats.degenerateTriangles;
            mesh.triangle(verts[tr[0]], verts[tr[1]], verts[tr[2]], false);
          }
          first += loops.size[l];
        }
      }
  return mesh;
}

TEST(CubeCases, RandomPatternsAssembleIntoAClosedManifold) {
  const int n = 9;
  for (std::uint32_t seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<char> solid(n * n * n, 0);
    for (int z = 1; z + 1 < n; ++z)
      for (int y = 1; y + 1 < n; ++y)
        for (int x = 1; x + 1 < n; ++x) solid[(z * n + y) * n + x] = unit(rng) < 0.3 + 0.1 * seed;
    std::vector<double> t(n * n * n * 3);
    for (double& x : t) x = 0.001 + 0.998 * unit(rng);
    MeshStats stats;
    const IndexedMesh mesh = assemble(n, solid, t, stats);
    const EdgeReport e = checkEdges(mesh);
    EXPECT_TRUE(e.closed()) << "seed " << seed << ": open " << e.open << " overused " << e.overused
                            << " flipped " << e.sameDirection;
    EXPECT_EQ(nonManifoldVertices(mesh), 0) << seed;
    EXPECT_EQ(stats.degenerateTriangles, 0) << seed;
    EXPECT_GT(enclosedVolume(mesh), 0.0) << seed;
  }
}

TEST(CubeCases, SphereFieldEnclosesTheSphere) {
  const int n = 24;
  const double r = 9.3, c = 11.5;
  std::vector<char> solid(n * n * n, 0);
  auto inside = [&](double x, double y, double z) {
    return (x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c) <= r * r;
  };
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) solid[(z * n + y) * n + x] = inside(x, y, z);
  // Exact crossings of the sphere on each grid edge.
  std::vector<double> t(n * n * n * 3, 0.5);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (int a = 0; a < 3; ++a) {
          glm::dvec3 p(x, y, z);
          const double du = p[(a + 1) % 3] - c, dv = p[(a + 2) % 3] - c;
          const double s = r * r - du * du - dv * dv;
          if (s < 0) continue;
          for (double root : {c - std::sqrt(s), c + std::sqrt(s)})
            if (root >= p[a] && root <= p[a] + 1) t[((z * n + y) * n + x) * 3 + a] = root - p[a];
        }
  MeshStats stats;
  const IndexedMesh mesh = assemble(n, solid, t, stats);
  EXPECT_TRUE(checkEdges(mesh).closed());
  const double exact = 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
  // Chords lie inside the sphere: a little less, by about area x sagitta
  // (r = 9.3 grid units: 0.6 %).
  EXPECT_LT(enclosedVolume(mesh), exact);
  EXPECT_NEAR(enclosedVolume(mesh), exact, 0.01 * exact);
}

}  // namespace
}  // namespace mdhd::mesh

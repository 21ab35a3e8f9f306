#include "sim/mesh/cube_cases.h"

#include <cmath>
#include <cstdint>

namespace mdhd::mesh {

namespace {

int cornerAt(int x, int y, int z) {
  return x | (y << 1) | (z << 2);
}

std::array<CubeEdge, 12> makeEdges() {
  std::array<CubeEdge, 12> e{};
  int n = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int c = 0; c < 8; ++c)
      if (!(c & (1 << axis))) e[n++] = CubeEdge{c, c | (1 << axis), axis};
  return e;
}

int edgeBetween(int a, int b) {
  const auto& edges = cubeEdges();
  for (int i = 0; i < 12; ++i)
    if ((edges[i].from == a && edges[i].to == b) || (edges[i].from == b && edges[i].to == a))
      return i;
  return -1;
}

std::array<CubeFace, 6> makeFaces() {
  std::array<CubeFace, 6> faces{};
  for (int f = 0; f < 6; ++f) {
    CubeFace& face = faces[f];
    face.axis = f / 2;
    face.side = f % 2;
    const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3;
    auto corner = [&](int cu, int cv) {
      int c[3];
      c[face.axis] = face.side;
      c[u] = cu;
      c[v] = cv;
      return cornerAt(c[0], c[1], c[2]);
    };
    face.frameCorners = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
    // u x v = +axis: counter-clockwise in (u, v) is counter-clockwise seen from +axis.
    if (face.side == 1)
      face.corners = face.frameCorners;
    else
      face.corners = {corner(0, 0), corner(0, 1), corner(1, 1), corner(1, 0)};
    for (int i = 0; i < 4; ++i)
      face.edges[i] = edgeBetween(face.corners[i], face.corners[(i + 1) % 4]);
    face.frameEdges = {
        edgeBetween(corner(0, 0), corner(1, 0)), edgeBetween(corner(0, 1), corner(1, 1)),
        edgeBetween(corner(0, 0), corner(0, 1)), edgeBetween(corner(1, 0), corner(1, 1))};
  }
  return faces;
}

}  // namespace

const std::array<CubeEdge, 12>& cubeEdges() {
  static const std::array<CubeEdge, 12> edges = makeEdges();
  return edges;
}

const std::array<CubeFace, 6>& cubeFaces() {
  static const std::array<CubeFace, 6> faces = makeFaces();
  return faces;
}

const std::array<unsigned, 12>& edgeFaceMasks() {
  static const std::array<unsigned, 12> masks = [] {
    std::array<unsigned, 12> m{};
    for (int f = 0; f < 6; ++f)
      for (int e : cubeFaces()[f].edges) m[e] |= 1u << f;
    return m;
  }();
  return masks;
}

unsigned crossingEdges(unsigned solid) {
  static const std::array<std::uint16_t, 256> table = [] {
    std::array<std::uint16_t, 256> m{};
    for (unsigned p = 0; p < 256; ++p)
      for (int e = 0; e < 12; ++e) {
        const CubeEdge& ce = cubeEdges()[e];
        if (((p >> ce.from) & 1u) != ((p >> ce.to) & 1u)) m[p] |= std::uint16_t(1u << e);
      }
    return m;
  }();
  return table[solid & 0xffu];
}

bool solidJoined(bool q00Solid, double su0, double su1, double sv0, double sv1) {
  // Segments cutting off q00 and q11, and those cutting off q10 and q01.
  const double around00and11 = std::hypot(su0, sv0) + std::hypot(1.0 - su1, 1.0 - sv1);
  const double around10and01 = std::hypot(1.0 - su0, sv1) + std::hypot(su1, 1.0 - sv0);
  // Joined solid corners: the segments go around the empty ones.
  return q00Solid ? around10and01 <= around00and11 : around00and11 <= around10and01;
}

int faceSegments(const CubeFace& face, unsigned solid, const double* t,
                 std::array<std::pair<int, int>, 2>& out) {
  bool in[4];
  for (int i = 0; i < 4; ++i) in[i] = (solid >> face.corners[i]) & 1u;
  int crossings = 0;
  for (int i = 0; i < 4; ++i) crossings += in[i] != in[(i + 1) % 4];
  if (crossings == 0) return 0;
  if (crossings == 2) {
    int enter = -1, exit = -1;
    for (int i = 0; i < 4; ++i) {
      if (!in[i] && in[(i + 1) % 4]) enter = face.edges[i];
      if (in[i] && !in[(i + 1) % 4]) exit = face.edges[i];
    }
    out[0] = {enter, exit};
    return 1;
  }
  // Ambiguous: every edge crosses, enters and exits alternate.
  const bool q00 = (solid >> face.frameCorners[0]) & 1u;
  const auto& fe = face.frameEdges;
  const bool joined = solidJoined(q00, t[fe[0]], t[fe[1]], t[fe[2]], t[fe[3]]);
  int n = 0;
  for (int i = 0; i < 4; ++i) {
    if (in[i] || !in[(i + 1) % 4]) continue;  // not an entering edge
    // Joined: the segment cuts off the empty corner before it (previous exit);
    // separated: it cuts off the solid corner after it (next exit).
    const int exitEdge = joined ? face.edges[(i + 3) % 4] : face.edges[(i + 1) % 4];
    out[n++] = {face.edges[i], exitEdge};
  }
  return n;
}

CubeLoops cubeLoopsRead(unsigned solid, const double* t) {
  int next[12];
  for (int& n : next) n = -1;
  std::array<std::pair<int, int>, 2> segs;
  for (const CubeFace& face : cubeFaces()) {
    const int n = faceSegments(face, solid, t, segs);
    for (int i = 0; i < n; ++i) next[segs[i].first] = segs[i].second;
  }
  CubeLoops loops;
  bool used[12] = {};
  int filled = 0;
  for (int start = 0; start < 12; ++start) {
    if (next[start] < 0 || used[start]) continue;
    int size = 0;
    for (int e = start; e >= 0 && !used[e]; e = next[e]) {
      used[e] = true;
      loops.edges[filled + size++] = e;
    }
    loops.size[loops.count++] = size;
    filled += size;
  }
  return loops;
}

bool hasAmbiguousFace(unsigned solid) {
  for (const CubeFace& face : cubeFaces()) {
    bool in[4];
    for (int i = 0; i < 4; ++i) in[i] = (solid >> face.corners[i]) & 1u;
    if (in[0] == in[2] && in[1] == in[3] && in[0] != in[1]) return true;
  }
  return false;
}

CubeLoops cubeLoops(unsigned solid, const double* t) {
  // A pattern without an ambiguous face reads the same whatever its crossings:
  // its loops are chained once, at first use, for all cubes.
  struct Table {
    std::array<CubeLoops, 256> loops{};
    std::array<bool, 256> ambiguous{};
  };
  static const Table table = [] {
    Table tab;
    double any[12];
    for (double& x : any) x = 0.5;
    for (unsigned p = 0; p < 256; ++p) {
      tab.ambiguous[p] = hasAmbiguousFace(p);
      if (!tab.ambiguous[p]) tab.loops[p] = cubeLoopsRead(p, any);
    }
    return tab;
  }();
  solid &= 0xffu;
  return table.ambiguous[solid] ? cubeLoopsRead(solid, t) : table.loops[solid];
}

}  // namespace mdhd::mesh

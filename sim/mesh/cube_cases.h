#pragma once
// Marching cubes for one grid cube, with the cases generated on the fly
// (thesis 4.3.2): each face is read as a marching square, its separating
// segments are chained into the cube's line loops.
//
// Corner i of a cube sits at offset (i & 1, (i >> 1) & 1, (i >> 2) & 1) from
// its min corner. A face is read from its own data only (4 corners, 4 edge
// crossings), so the two cubes beside a face always read it the same way:
// that is what makes the mesh seamless.
#include <array>
#include <utility>

namespace mdhd::mesh {

struct CubeEdge {
  int from = 0;  // the corner with the lower coordinate
  int to = 0;
  int axis = 0;
};

struct CubeFace {
  int axis = 0;
  int side = 0;                // 0: the face at the cube's low coordinate
  std::array<int, 4> corners;  // counter-clockwise seen from outside the cube
  std::array<int, 4> edges;    // edges[i] joins corners[i] and corners[(i + 1) % 4]
  // In the face's own (u, v) frame, u = (axis + 1) % 3, v = (axis + 2) % 3:
  // corners q00 q10 q11 q01 and edges u0 (v = 0), u1 (v = 1), v0 (u = 0), v1 (u = 1).
  std::array<int, 4> frameCorners;
  std::array<int, 4> frameEdges;
};

const std::array<CubeEdge, 12>& cubeEdges();
const std::array<CubeFace, 6>& cubeFaces();
// Bit f set when edge e lies on face f, for all twelve edges.
const std::array<unsigned, 12>& edgeFaceMasks();
inline unsigned edgeFaces(int edge) {
  return edgeFaceMasks()[edge];
}
// Bit e set when the pattern's corners differ at the ends of edge e.
unsigned crossingEdges(unsigned solid);

// The ambiguous square: two diagonally opposite solid corners. `q00Solid`
// says which diagonal is solid; s* are the crossings (0..1 from the low end)
// on the edges u0 u1 v0 v1. True when the solid corners are joined: the
// reading whose separating segments are shorter, the joined one on a tie
// (the thesis's single interpretation). Depends on the face's data only.
bool solidJoined(bool q00Solid, double su0, double su1, double sv0, double sv1);

// The separating segments of a face, each from the edge where the walk
// counter-clockwise (seen from outside) enters solid to the edge where it
// leaves. `solid`: bit i for cube corner i; `t`: crossings per cube edge.
int faceSegments(const CubeFace& face, unsigned solid, const double* t,
                 std::array<std::pair<int, int>, 2>& out);

// The cube's line loops, as cube edge ids. Each loop runs counter-clockwise
// seen from the empty side, so it bounds a surface patch with outward normal.
struct CubeLoops {
  int count = 0;
  std::array<int, 6> size{};
  std::array<int, 12> edges{};  // loop after loop
};

// Patterns without an ambiguous face come from a table built once; the rest are
// read face by face (cubeLoopsRead).
CubeLoops cubeLoops(unsigned solid, const double* t);
// The loops chained from the faces' segments for this cube's crossings (what the
// table holds for the unambiguous patterns).
CubeLoops cubeLoopsRead(unsigned solid, const double* t);
// Whether a face of the pattern has two diagonally opposite solid corners only.
bool hasAmbiguousFace(unsigned solid);

}  // namespace mdhd::mesh

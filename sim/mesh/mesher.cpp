#include "sim/mesh/mesher.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/mesh/cube_cases.h"
#include "sim/mesh/loop_triangulation.h"
#include "sim/mesh/parallel_runs.h"
#include "sim/mesh/stock_view.h"

namespace mdhd::mesh {

namespace {

GridPoint cornerOf(const GridPoint& c, int corner) {
  return {c[0] + (corner & 1), c[1] + ((corner >> 1) & 1), c[2] + ((corner >> 2) & 1)};
}

// A cube's corner pattern from its four corner columns (d: u + (d & 1), v + (d >> 1)
// on a map of axis a), each solid or not at the cube's lower and upper level.
struct ColumnCorners {
  ColumnCorners(int a, int u, int v) : up(1u << a) {
    for (int d = 0; d < 4; ++d) low[d] = 1u << (((d & 1) << u) | ((d >> 1) << v));
  }
  unsigned bits(int d, bool lower, bool upper) const {
    return (lower ? low[d] : 0u) | (upper ? low[d] << up : 0u);  // corner i + 2^a is i one up
  }
  unsigned low[4];
  unsigned up;
};

// One polygon vertex while a loop is assembled: grid position and identity.
struct LoopPoint {
  glm::dvec3 g{0.0};
  VertexKey key;
  std::uint8_t faces = 0;
};

class Mesher {
 public:
  Mesher(const StockView& view, MeshSink& sink, MeshStats& stats)
      : view_(view), sink_(sink), stats_(stats), margin_(crossingMargin(view)) {}

  void interior(int leaf);
  void exterior(int leaf);

 private:
  void cube(const GridPoint& c);
  // A cube whose corners' solidity is known (bit i: corner i). `owned`: the leaf
  // hint_ owns all eight corners, so its crossings need no owner lookup.
  void surfaceCube(const GridPoint& c, unsigned solid, bool owned);
  void foreignColumn(const LeafInfo& l, GridPoint c);
  void walkColumn(const LeafInfo& l, int pu, int pv, std::uint8_t* out);
  void square(const GridPoint& cubeMin, int face);
  bool faceStates(const LeafInfo& l, int faceId);
  void mergedFace(const LeafInfo& l, int faceId);
  void solidStrips(const LeafInfo& l, int faceId);
  void strip(const LeafInfo& l, int faceId, int s);
  void partialLeaf(const LeafInfo& l);
  void uniformLeaf(const LeafInfo& l);
  double edgeT(const GridPoint& p, int axis, bool startSolid, bool owned = false);
  LoopPoint crossingPoint(const GridPoint& p, int axis, double t) const;
  void emit(std::span<const LoopPoint> loop, bool exterior);
  // `checked`: its area is known to be above kMinDoubleArea.
  void triangle(const LoopPoint& a, const LoopPoint& b, const LoopPoint& c, bool exterior,
                bool checked = false);
  MeshVertex vertex(const LoopPoint& p) const {
    return MeshVertex{view_.origin() + p.g * view_.spacing(), p.key};
  }

  const StockView& view_;
  MeshSink& sink_;
  MeshStats& stats_;
  const double margin_;  // crossingMargin(view_)
  // The owner of a vertex: the leaf being meshed, else the last other owner met
  // (the leaf across a face owns runs of vertices), else a search.
  int vertexOwner(const GridPoint& p) {
    if (view_.owns(hint_, p)) return hint_;
    foreign_ = view_.ownerOf(p, foreign_);
    return foreign_;
  }
  bool solidAt(const GridPoint& p) { return view_.solidOwnedBy(vertexOwner(p), p); }

  // Recent crossings by edge: a grid edge is shared by up to four cubes and squares,
  // each of which asked its owner again. Direct-mapped; what an edge's owner says does
  // not depend on who asks, so a hit gives the same bits.
  struct Memo {
    std::uint64_t where = ~std::uint64_t{0};
    int axis = -1;
    double t = 0.0;
  };
  static constexpr int kMemoBits = 10;
  std::array<Memo, std::size_t{1} << kMemoBits> memo_{};

  int hint_ = -1;     // the leaf being meshed
  int foreign_ = -1;  // the last vertex owner other than hint_
  std::uint64_t nextInner_ = 0;
  std::vector<std::array<int, 3>> tris_;
  std::vector<glm::dvec3> pts_;
  std::vector<std::uint8_t> masks_;
  std::vector<LoopPoint> rim_;
  std::array<LoopPoint, 12> loop_;  // surfaceCube's loop being emitted
  // foreignColumn: the leaf's own corner columns, and the last few walked ones
  // (keyed by leaf and position: far-side columns next to each other share two).
  struct ForeignColumn {
    int leaf = -1, pu = 0, pv = 0;
    std::vector<std::uint8_t> states;
  };
  std::array<std::vector<std::uint8_t>, 4> ownColumn_;
  std::array<ForeignColumn, 4> walked_;
  std::size_t nextWalked_ = 0;
  std::vector<std::uint8_t> topFace_;  // partialLeaf: the states of a foreign top face
  // Its vertex at (pu, pv) on the leaf's u and v axes.
  std::uint8_t& topFaceAt(const LeafInfo& l, int pu, int pv) {
    const int u = (l.axis + 1) % 3, v = (l.axis + 2) % 3;
    return topFace_[static_cast<std::size_t>(pv - l.lo[v]) * (l.hi[u] - l.lo[u] + 1) +
                    (pu - l.lo[u])];
  }
  std::vector<std::uint8_t> face_;  // exterior: the states of a boundary face
  // exterior: per strip of a partial leaf's side face, the full squares from the base
  std::vector<int> stripRun_;
  std::vector<std::pair<LoopPoint, int>> sideA_, sideB_;  // strip: a chain's points, levels
};

double Mesher::edgeT(const GridPoint& p, int axis, bool startSolid, bool owned) {
  const std::uint64_t where = packGridVertex(p[0], p[1], p[2]);
  Memo& memo = memo_[((where * 3 + static_cast<std::uint64_t>(axis)) * 0x9e3779b97f4a7c15ull) >>
                     (64 - kMemoBits)];
  if (memo.where == where && memo.axis == axis) return memo.t;
  const double x = view_.crossingOwnedBy(owned ? hint_ : vertexOwner(p), p, axis);
  double t = x - p[axis];
  if (!std::isfinite(t)) {
    // The edge's owner sees no surface here, the end's owner does: in practice a
    // solid interval ending right on the shared vertex, so the crossing goes there
    // (not remembered: counted each time, as before the memo).
    ++stats_.fallbackCrossings;
    t = startSolid ? 0.0 : 1.0;
    return std::clamp(t, margin_, 1.0 - margin_);
  }
  t = std::clamp(t, margin_, 1.0 - margin_);
  memo = {where, axis, t};
  return t;
}

LoopPoint Mesher::crossingPoint(const GridPoint& p, int axis, double t) const {
  LoopPoint q;
  q.g = glm::dvec3(p[0], p[1], p[2]);
  q.g[axis] += t;
  q.key = VertexKey{packGridVertex(p[0], p[1], p[2]), static_cast<VertexKind>(axis)};
  return q;
}

void Mesher::emit(std::span<const LoopPoint> loop, bool exterior) {
  pts_.clear();
  masks_.clear();
  for (const LoopPoint& p : loop) {
    pts_.push_back(p.g);
    masks_.push_back(p.faces);
  }
  tris_.clear();
  glm::dvec3 centre(0.0);
  const bool plain = triangulateLoop(pts_, masks_, tris_, centre);
  LoopPoint mid;
  if (!plain) {
    ++stats_.centreVertices;
    mid.g = centre;
    mid.key = VertexKey{nextInner_++, VertexKind::kInner};
  }
  const int n = static_cast<int>(loop.size());
  // A fan chosen from more than three corners had every triangle's area checked.
  const bool checked = plain && n > 3;
  for (const auto& t : tris_)
    triangle(t[0] == n ? mid : loop[t[0]], t[1] == n ? mid : loop[t[1]],
             t[2] == n ? mid : loop[t[2]], exterior, checked);
}

void Mesher::triangle(const LoopPoint& a, const LoopPoint& b, const LoopPoint& c, bool exterior,
                      bool checked) {
  if (!checked && glm::length(glm::cross(b.g - a.g, c.g - a.g)) <= kMinDoubleArea)
    ++stats_.degenerateTriangles;
  sink_.triangle(vertex(a), vertex(b), vertex(c), exterior);
  ++stats_.triangles;
  stats_.exteriorTriangles += exterior ? 1 : 0;
}

void Mesher::cube(const GridPoint& c) {
  unsigned solid = 0;
  for (int i = 0; i < 8; ++i)
    if (solidAt(cornerOf(c, i))) solid |= 1u << i;
  surfaceCube(c, solid, false);
}

void Mesher::surfaceCube(const GridPoint& c, unsigned solid, bool owned) {
  if (solid == 0 || solid == 0xffu) return;
  const auto& edges = cubeEdges();
  const auto& faces = edgeFaceMasks();
  double t[12];
  std::fill(std::begin(t), std::end(t), 0.5);
  for (unsigned m = crossingEdges(solid); m != 0; m &= m - 1) {
    const int e = std::countr_zero(m);
    t[e] = edgeT(cornerOf(c, edges[e].from), edges[e].axis, (solid >> edges[e].from) & 1u, owned);
  }
  const CubeLoops loops = cubeLoops(solid, t);
  ++stats_.surfaceCubes;
  int at = 0;
  LoopPoint* loop = loop_.data();  // a member: no twelve points to initialise per cube
  for (int l = 0; l < loops.count; ++l) {
    for (int k = 0; k < loops.size[l]; ++k) {
      const int e = loops.edges[at + k];
      loop[k] = crossingPoint(cornerOf(c, edges[e].from), edges[e].axis, t[e]);
      loop[k].faces = static_cast<std::uint8_t>(faces[e]);
    }
    emit(std::span<const LoopPoint>(loop, loops.size[l]), false);
    at += loops.size[l];
    ++stats_.loops;
  }
}

void Mesher::square(const GridPoint& cubeMin, int faceId) {
  const CubeFace& face = cubeFaces()[faceId];
  const auto& edges = cubeEdges();
  unsigned solid = 0;
  for (int corner : face.corners)
    if (solidAt(cornerOf(cubeMin, corner))) solid |= 1u << corner;
  if (solid == 0) return;
  double t[12] = {};
  // Items counter-clockwise from outside: corner i, then the crossing on edge i.
  LoopPoint items[8];
  bool isCorner[8] = {}, isExit[8] = {}, present[8] = {};
  int itemOfEdge[12];
  for (int i = 0; i < 4; ++i) {
    const int c0 = face.corners[i], c1 = face.corners[(i + 1) % 4], e = face.edges[i];
    const bool s0 = (solid >> c0) & 1u, s1 = (solid >> c1) & 1u;
    if (s0) {
      const GridPoint p = cornerOf(cubeMin, c0);
      items[2 * i].g = glm::dvec3(p[0], p[1], p[2]);
      items[2 * i].key = VertexKey{packGridVertex(p[0], p[1], p[2]), VertexKind::kCorner};
      isCorner[2 * i] = present[2 * i] = true;
    }
    itemOfEdge[e] = 2 * i + 1;
    if (s0 != s1) {
      t[e] = edgeT(cornerOf(cubeMin, edges[e].from), edges[e].axis, (solid >> edges[e].from) & 1u);
      items[2 * i + 1] = crossingPoint(cornerOf(cubeMin, edges[e].from), edges[e].axis, t[e]);
      present[2 * i + 1] = true;
      isExit[2 * i + 1] = s0;
    }
  }
  std::array<std::pair<int, int>, 2> segs;
  const int nseg = faceSegments(face, solid, t, segs);
  int jump[8];
  for (int i = 0; i < nseg; ++i) jump[itemOfEdge[segs[i].second]] = itemOfEdge[segs[i].first];
  bool used[8] = {};
  LoopPoint poly[8];
  for (int start = 0; start < 8; start += 2) {
    if (!isCorner[start] || used[start]) continue;
    int n = 0;
    int k = start;
    do {
      used[k] = true;
      poly[n++] = items[k];
      if (isExit[k]) {
        k = jump[k];
        used[k] = true;
        poly[n++] = items[k];
      }
      do k = (k + 1) % 8;
      while (!present[k]);
    } while (k != start && n < 8);
    emit(std::span<const LoopPoint>(poly, n), true);
  }
}

// The states of the grid vertices of the leaf's face on the stock's boundary
// (face_, u fastest, u and v as in CubeFace), walked once from owner to owner;
// true if all are solid.
bool Mesher::faceStates(const LeafInfo& l, int faceId) {
  const CubeFace& face = cubeFaces()[faceId];
  const int a = face.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  face_.clear();
  bool all = true;
  GridPoint p{};
  p[a] = face.side == 0 ? l.lo[a] : l.hi[a];
  // The leaf owns all but the face's far row and column (unless they lie on the
  // stock's far sides): those are read from it without an owner lookup.
  const GridPoint& n = view_.cubes();
  const int ownU = l.hi[u] == n[u] ? l.hi[u] : l.hi[u] - 1;
  const int ownV = l.hi[v] == n[v] ? l.hi[v] : l.hi[v] - 1;
  int owner = hint_;
  for (p[v] = l.lo[v]; p[v] <= l.hi[v]; ++p[v])
    for (p[u] = l.lo[u]; p[u] <= l.hi[u]; ++p[u]) {
      const bool in =
          p[u] <= ownU && p[v] <= ownV ? view_.solidOwnedBy(hint_, p) : view_.solidWalk(p, owner);
      face_.push_back(in);
      all = all && in;
    }
  return all;
}

// A leaf's boundary face that is solid all over, as one polygon: every grid
// vertex on its rim (the neighbouring faces' triangles end there, so the mesh
// stays closed) fanned from a vertex added at its centre. 4n triangles for an
// n x n face instead of 2n^2: the stock's untouched sides and floor no longer
// dominate the mesh.
void Mesher::mergedFace(const LeafInfo& l, int faceId) {
  const CubeFace& face = cubeFaces()[faceId];
  const int a = face.axis;
  // The rectangle's corners in the cube face's order (counter-clockwise seen from
  // outside), then the grid vertices from each to the next.
  GridPoint corner[4];
  for (int i = 0; i < 4; ++i)
    for (int b = 0; b < 3; ++b)
      corner[i][b] = b == a ? (face.side == 0 ? l.lo[a] : l.hi[a])
                            : (((face.corners[i] >> b) & 1) ? l.hi[b] : l.lo[b]);
  rim_.clear();
  for (int i = 0; i < 4; ++i) {
    const GridPoint& from = corner[i];
    const GridPoint& to = corner[(i + 1) % 4];
    int along = 0;
    while (along < 3 && from[along] == to[along]) ++along;
    const int step = to[along] > from[along] ? 1 : -1;
    for (GridPoint p = from; p[along] != to[along]; p[along] += step) {
      LoopPoint q;
      q.g = glm::dvec3(p[0], p[1], p[2]);
      q.key = VertexKey{packGridVertex(p[0], p[1], p[2]), VertexKind::kCorner};
      rim_.push_back(q);
    }
  }
  LoopPoint mid;
  for (const LoopPoint& q : rim_) mid.g += q.g;
  mid.g /= double(rim_.size());
  mid.key = VertexKey{nextInner_++, VertexKind::kInner};
  ++stats_.centreVertices;
  const std::size_t n = rim_.size();
  for (std::size_t i = 0; i < n; ++i) triangle(mid, rim_[i], rim_[(i + 1) % n], true);
}

// The side face of a partial leaf (a face along its map's axis) is solid from the
// columns' base up to about the surface: square by square that is two triangles per
// grid square of the stock's walls. Each strip between two neighbouring columns has
// its run of all-solid squares from the base meshed as one rectangle instead, with
// vertices on its sides only where something else meets them: the squares above the
// neighbouring strip's shorter run, and every grid vertex on the leaf's own rim (the
// neighbouring leaves' faces). stripRun_ gets each strip's run.
void Mesher::solidStrips(const LeafInfo& l, int faceId) {
  const CubeFace& face = cubeFaces()[faceId];
  const int a = face.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const int m = l.axis, w = m == u ? v : u;
  const int fu = l.hi[u] - l.lo[u] + 1;
  const int strips = l.hi[w] - l.lo[w], levels = l.hi[m] - l.lo[m];
  // face_ at the strip's line `line` (0..strips) and level k above the leaf's bottom.
  const auto solid = [&](int line, int k) {
    const int iu = m == u ? k : line, iv = m == u ? line : k;
    return face_[static_cast<std::size_t>(iv) * fu + iu] != 0;
  };
  stripRun_.assign(static_cast<std::size_t>(strips), 0);
  for (int s = 0; s < strips; ++s) {
    int run = 0;  // full squares from the base: both lines solid at run + 1 levels
    for (int r = 0; r <= levels; ++r) {
      const int k = l.sign > 0 ? r : levels - r;
      if (!solid(s, k) || !solid(s + 1, k)) break;
      run = r;
    }
    stripRun_[static_cast<std::size_t>(s)] = run;
  }
  for (int s = 0; s < strips; ++s)
    if (stripRun_[static_cast<std::size_t>(s)] > 0) strip(l, faceId, s);
}

// One strip's rectangle: two chains up its sides from the base, zipped together.
void Mesher::strip(const LeafInfo& l, int faceId, int s) {
  const CubeFace& face = cubeFaces()[faceId];
  const int a = face.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const int m = l.axis, w = m == u ? v : u;
  const int strips = l.hi[w] - l.lo[w];
  const int run = stripRun_[static_cast<std::size_t>(s)];
  const auto chain = [&](std::vector<std::pair<LoopPoint, int>>& out, int line, int neighbour) {
    // The neighbouring strip's run, or 0 at the leaf's rim: every level is met there.
    const int other =
        neighbour < 0 || neighbour >= strips ? 0 : stripRun_[static_cast<std::size_t>(neighbour)];
    out.clear();
    GridPoint p{};
    p[a] = face.side == 0 ? l.lo[a] : l.hi[a];
    p[w] = l.lo[w] + line;
    for (int r = 0; r <= run; ++r) {
      if (r != 0 && r != run && r < other) continue;
      p[m] = l.sign > 0 ? l.lo[m] + r : l.hi[m] - r;
      LoopPoint q;
      q.g = glm::dvec3(p[0], p[1], p[2]);
      q.key = VertexKey{packGridVertex(p[0], p[1], p[2]), VertexKind::kCorner};
      out.emplace_back(q, r);
    }
  };
  chain(sideA_, s, s - 1);
  chain(sideB_, s + 1, s + 1);
  glm::dvec3 outward(0.0);
  outward[a] = face.side == 0 ? -1.0 : 1.0;
  const auto emitOriented = [&](const LoopPoint& p, const LoopPoint& q, const LoopPoint& r) {
    if (glm::dot(glm::cross(q.g - p.g, r.g - p.g), outward) >= 0.0)
      triangle(p, q, r, true);
    else
      triangle(p, r, q, true);
  };
  std::size_t i = 0, j = 0;
  const std::size_t na = sideA_.size(), nb = sideB_.size();
  while (i + 1 < na || j + 1 < nb) {
    if (j + 1 == nb || (i + 1 < na && sideA_[i + 1].second <= sideB_[j + 1].second)) {
      emitOriented(sideA_[i].first, sideA_[i + 1].first, sideB_[j].first);
      ++i;
    } else {
      emitOriented(sideA_[i].first, sideB_[j].first, sideB_[j + 1].first);
      ++j;
    }
  }
}

void Mesher::uniformLeaf(const LeafInfo& l) {
  const bool solid = l.kind == LeafKind::kSolid;
  const GridPoint& n = view_.cubes();
  bool layer[3] = {};
  for (int a = 0; a < 3; ++a) {
    if (l.hi[a] == n[a]) continue;  // the grid's top plane is this leaf's own
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    GridPoint p{};
    p[a] = l.hi[a];
    p[u] = l.lo[u];
    p[v] = l.lo[v];
    // The face's vertices belong to the neighbours. The one owning its first corner
    // owns a rectangle of it from there; when that neighbour is uniform, its kind
    // answers for the whole rectangle (bricks side by side: all of the face but the
    // far rows), and only the rest is walked.
    int owner = view_.ownerOf(p, hint_);
    const LeafInfo& across = view_.leaf(owner);
    int uEnd = l.lo[u] - 1, vEnd = l.lo[v] - 1;  // the rectangle's last vertices
    if (across.kind != LeafKind::kPartial) {
      if ((across.kind == LeafKind::kSolid) != solid) {
        layer[a] = true;
        continue;
      }
      uEnd = across.hi[u] == n[u] ? n[u] : across.hi[u] - 1;
      vEnd = across.hi[v] == n[v] ? n[v] : across.hi[v] - 1;
    }
    for (p[v] = l.lo[v]; p[v] <= l.hi[v] && !layer[a]; ++p[v])
      for (p[u] = p[v] <= vEnd ? std::max(l.lo[u], uEnd + 1) : l.lo[u]; p[u] <= l.hi[u]; ++p[u]) {
        if (view_.solidWalk(p, owner) != solid) {
          layer[a] = true;
          break;
        }
      }
  }
  // Only the cube layers under a hi face with a disagreeing vertex can hold surface.
  for (int a = 0; a < 3; ++a) {
    if (!layer[a]) continue;
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    GridPoint c{};
    c[a] = l.hi[a] - 1;
    for (c[v] = l.lo[v]; c[v] < l.hi[v]; ++c[v])
      for (c[u] = l.lo[u]; c[u] < l.hi[u]; ++c[u]) {
        bool done = false;  // already met in an earlier marked layer
        for (int b = 0; b < a; ++b) done = done || (layer[b] && c[b] == l.hi[b] - 1);
        if (!done) cube(c);
      }
  }
}

// A column of cubes on the leaf's far side: some corners belong to the neighbours, and
// their columns may hold the surface at any level. Each corner column is read once:
// the leaf's own from its column count (and topFace_ at a foreign top), the others
// walked from owner to owner and kept for the next far-side column, which shares two
// corner columns with this one. Only the cubes whose corners disagree are meshed.
// The solidity of the column through (pu, pv) over leaf l's levels, as the vertices'
// owners store it: a run of levels at a time per owner (a uniform leaf, or a map of
// l's direction, answers for all its levels at once), vertex by vertex otherwise.
void Mesher::walkColumn(const LeafInfo& l, int pu, int pv, std::uint8_t* out) {
  const int a = l.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const GridPoint& n = view_.cubes();
  GridPoint p{};
  p[u] = pu;
  p[v] = pv;
  int owner = hint_;
  for (int k = l.lo[a]; k <= l.hi[a];) {
    p[a] = k;
    owner = view_.ownerOf(p, owner);
    const LeafInfo& o = view_.leaf(owner);
    const int end = std::min(l.hi[a], o.hi[a] == n[a] ? n[a] : o.hi[a] - 1);  // owned levels
    std::uint8_t* at = out + (k - l.lo[a]);
    const int count = end - k + 1;
    if (o.kind != LeafKind::kPartial) {
      std::fill(at, at + count, o.kind == LeafKind::kSolid ? 1 : 0);
    } else if (o.axis == a && o.sign == l.sign && !o.twoSided) {
      // Solid below (+) or above (-) the owner's column surface.
      const int solid = view_.columnSolidCount(owner, p[u], p[v]);
      const int edge = o.sign > 0 ? o.lo[a] + solid : o.hi[a] - solid + 1;
      // Levels below `edge` are solid in a + map, those from it on in a - map.
      const int below = std::clamp(edge - k, 0, count);
      std::fill(at, at + below, o.sign > 0 ? 1 : 0);
      std::fill(at + below, at + count, o.sign > 0 ? 0 : 1);
    } else {
      for (int i = 0; i < count; ++i) {
        p[a] = k + i;
        at[i] = view_.solidOwnedBy(owner, p);
      }
    }
    k = end + 1;
  }
}

void Mesher::foreignColumn(const LeafInfo& l, GridPoint c) {
  const int a = l.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const GridPoint& n = view_.cubes();
  const int levels = l.hi[a] - l.lo[a] + 1;
  const bool topForeign = l.hi[a] < n[a];
  const std::uint8_t* col[4];
  unsigned inUse = 0;  // walked_ entries this column reads
  for (int d = 0; d < 4; ++d) {
    const int pu = c[u] + (d & 1), pv = c[v] + (d >> 1);
    const bool own = (pu < l.hi[u] || l.hi[u] == n[u]) && (pv < l.hi[v] || l.hi[v] == n[v]);
    if (own) {
      ownColumn_[d].resize(static_cast<std::size_t>(levels));
      std::uint8_t* out = ownColumn_[d].data();
      const int k = view_.columnSolidCount(hint_, pu, pv);
      const int below = l.sign > 0 ? k : levels - k;  // levels before the column's change
      std::fill(out, out + below, l.sign > 0 ? 1 : 0);
      std::fill(out + below, out + levels, l.sign > 0 ? 0 : 1);
      if (topForeign) out[levels - 1] = topFaceAt(l, pu, pv);
      col[d] = out;
      continue;
    }
    ForeignColumn* hit = nullptr;
    for (std::size_t i = 0; i < walked_.size(); ++i)
      if (walked_[i].leaf == hint_ && walked_[i].pu == pu && walked_[i].pv == pv) {
        hit = &walked_[i];
        inUse |= 1u << i;
      }
    if (hit == nullptr) {
      // The oldest entry not read by this column already.
      while (inUse & (1u << nextWalked_)) nextWalked_ = (nextWalked_ + 1) % walked_.size();
      inUse |= 1u << nextWalked_;
      hit = &walked_[nextWalked_];
      nextWalked_ = (nextWalked_ + 1) % walked_.size();
      hit->leaf = hint_;
      hit->pu = pu;
      hit->pv = pv;
      hit->states.resize(static_cast<std::size_t>(levels));
      walkColumn(l, pu, pv, hit->states.data());
    }
    col[d] = hit->states.data();
  }
  // Below the first level where any column leaves its base state (solid for a + map)
  // and above the last, all four agree: only the cubes between can hold surface.
  const std::uint8_t base = l.sign > 0 ? 1 : 0;
  int first = levels, last = -1;
  for (int d = 0; d < 4; ++d) {
    // States are 0 or 1. The first change is the first level off the base state; the
    // last is the one after the last level in the base state, or the far side (which
    // differs from the base) when the column ends in it.
    const auto* s = col[d];
    const auto* off = static_cast<const std::uint8_t*>(std::memchr(s, base ^ 1, levels));
    first = std::min(first, off != nullptr ? static_cast<int>(off - s) : levels);
    if (s[levels - 1] == base) {
      last = levels;
    } else {
      const auto* on = static_cast<const std::uint8_t*>(memrchr(s, base, levels));
      last = std::max(last, on != nullptr ? static_cast<int>(on - s) + 1 : 0);
    }
  }
  const ColumnCorners corners(a, u, v);
  for (int j = std::max(0, first - 1); j + 1 < levels && j <= last - 1; ++j) {
    unsigned solid = 0;
    for (int d = 0; d < 4; ++d) solid |= corners.bits(d, col[d][j] != 0, col[d][j + 1] != 0);
    if (solid == 0 || solid == 0xffu) continue;
    c[a] = l.lo[a] + j;
    surfaceCube(c, solid, false);
  }
}

void Mesher::partialLeaf(const LeafInfo& l) {
  const int a = l.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const GridPoint& n = view_.cubes();
  const int cubesA = l.hi[a] - l.lo[a], levels = cubesA + 1;
  const bool topForeign = l.hi[a] < n[a];
  // Under a foreign top face every column's top cube is looked at: the face's
  // vertices (other leaves own them) are read once, walking from owner to owner,
  // instead of four owner lookups per cube.
  if (topForeign) {
    topFace_.resize(static_cast<std::size_t>(l.hi[u] - l.lo[u] + 1) * (l.hi[v] - l.lo[v] + 1));
    GridPoint p{};
    p[a] = l.hi[a];
    int owner = hint_;
    for (p[v] = l.lo[v]; p[v] <= l.hi[v]; ++p[v])
      for (p[u] = l.lo[u]; p[u] <= l.hi[u]; ++p[u])
        topFaceAt(l, p[u], p[v]) = view_.solidWalk(p, owner);
  }
  // The pattern of a cube at layer j whose lower corners the leaf owns: from the
  // columns' counts, the upper corners at the top layer from topFace_.
  const ColumnCorners corners(a, u, v);
  const auto ownedPattern = [&](const GridPoint& c, int j, const int* counts) {
    const bool topRead = topForeign && j + 1 == levels - 1;
    unsigned solid = 0;
    for (int d = 0; d < 4; ++d) {
      const int k = counts[d];
      const bool lower = l.sign > 0 ? j < k : j >= levels - k;
      const bool upper = topRead ? topFaceAt(l, c[u] + (d & 1), c[v] + (d >> 1)) != 0
                                 : (l.sign > 0 ? j + 1 < k : j + 1 >= levels - k);
      solid |= corners.bits(d, lower, upper);
    }
    return solid;
  };
  // hint_ is this leaf: columnSolidCount reads it directly.
  GridPoint c{};
  for (c[v] = l.lo[v]; c[v] < l.hi[v]; ++c[v])
    for (c[u] = l.lo[u]; c[u] < l.hi[u]; ++c[u]) {
      if ((c[u] + 1 == l.hi[u] && l.hi[u] < n[u]) || (c[v] + 1 == l.hi[v] && l.hi[v] < n[v])) {
        foreignColumn(l, c);
        continue;
      }
      int nmin = levels, nmax = 0;
      int counts[4];  // solid vertices of the columns at u + (d & 1), v + (d >> 1)
      for (int d = 0; d < 4; ++d) {
        const int k = view_.columnSolidCount(hint_, c[u] + (d & 1), c[v] + (d >> 1));
        counts[d] = k;
        nmin = std::min(nmin, k);
        nmax = std::max(nmax, k);
      }
      // Only cubes between the lowest and the highest column's surface can hold it.
      const int j0 = l.sign > 0 ? std::max(0, nmin - 1) : std::max(0, levels - nmax - 1);
      const int j1 =
          l.sign > 0 ? std::min(cubesA - 1, nmax - 1) : std::min(cubesA - 1, levels - nmin - 1);
      // Cubes below the leaf's top layer, away from its far sides: the leaf owns
      // all eight corners, whose solidity the four columns' counts give.
      const int ownTop = topForeign ? cubesA - 2 : cubesA - 1;
      for (int j = j0; j <= j1; ++j) {
        c[a] = l.lo[a] + j;
        // The top layer under a foreign face: not all corners are the leaf's.
        surfaceCube(c, ownedPattern(c, j, counts), j <= ownTop);
      }
      if (topForeign && !(j0 <= cubesA - 1 && cubesA - 1 <= j1)) {  // not met above
        c[a] = l.hi[a] - 1;
        surfaceCube(c, ownedPattern(c, cubesA - 1, counts), false);
      }
    }
}

void Mesher::interior(int leaf) {
  hint_ = leaf;
  const LeafInfo& l = view_.leaf(leaf);
  if (l.kind == LeafKind::kPartial && l.twoSided) {
    // Columns on both sides: no run of levels per column to walk; every cube, from
    // its corners.
    GridPoint c{};
    for (c[2] = l.lo[2]; c[2] < l.hi[2]; ++c[2])
      for (c[1] = l.lo[1]; c[1] < l.hi[1]; ++c[1])
        for (c[0] = l.lo[0]; c[0] < l.hi[0]; ++c[0]) cube(c);
  } else if (l.kind == LeafKind::kPartial) {
    partialLeaf(l);
  } else {
    uniformLeaf(l);
  }
}

void Mesher::exterior(int leaf) {
  hint_ = leaf;
  const LeafInfo& l = view_.leaf(leaf);
  const GridPoint& n = view_.cubes();
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      if (side == 0 ? l.lo[a] != 0 : l.hi[a] != n[a]) continue;
      if (faceStates(l, 2 * a + side)) {
        mergedFace(l, 2 * a + side);
        continue;
      }
      // A side of a partial leaf: the solid squares from the columns' base up, strip by
      // strip, as rectangles (solidStrips); the rest square by square.
      const bool strips = l.kind == LeafKind::kPartial && a != l.axis && !l.twoSided;
      if (strips) solidStrips(l, 2 * a + side);
      const int m = l.axis, levels = l.hi[m] - l.lo[m];
      // Squares without a solid corner have nothing on them (a machined top face).
      const int fu = l.hi[u] - l.lo[u] + 1;
      GridPoint c{};
      c[a] = side == 0 ? 0 : n[a] - 1;
      for (c[v] = l.lo[v]; c[v] < l.hi[v]; ++c[v])
        for (c[u] = l.lo[u]; c[u] < l.hi[u]; ++c[u]) {
          if (strips) {
            const int w = m == u ? v : u;
            const int run = stripRun_[static_cast<std::size_t>(c[w] - l.lo[w])];
            const int k = c[m] - l.lo[m];  // the square's level above the leaf's bottom
            if (l.sign > 0 ? k < run : k >= levels - run) continue;
          }
          const std::size_t i = static_cast<std::size_t>(c[v] - l.lo[v]) * fu + (c[u] - l.lo[u]);
          if (face_[i] || face_[i + 1] || face_[i + fu] || face_[i + fu + 1])
            square(c, 2 * a + side);
        }
    }
  }
}

bool overlaps(const LeafInfo& l, const StockView& view, const geom::Aabb& region) {
  for (int a = 0; a < 3; ++a) {
    const double lo = view.origin()[a] + l.lo[a] * view.spacing();
    const double hi = view.origin()[a] + l.hi[a] * view.spacing();
    if (hi < region.lo[a] || lo > region.hi[a]) return false;
  }
  return true;
}

// A leaf's meshing work, about its triangles (so runs of equal work hold about
// equal triangles; measured on the example jobs' leaves): a partial leaf 2 per
// column (1.2 on average, up to 3.9 on a wall), 2 per grid square of a face across
// its map on the stock's boundary box and about 4 per strip of a side; a uniform
// leaf a fan round the rim of each boundary face and a scan of its top faces (a
// lookup per vertex, far cheaper).
std::int64_t workOf(const LeafInfo& l, const GridPoint& n) {
  const bool partial = l.kind == LeafKind::kPartial;
  std::int64_t work = 1;
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const std::int64_t du = l.hi[u] - l.lo[u], dv = l.hi[v] - l.lo[v];
    const int faces = (l.lo[a] == 0 ? 1 : 0) + (l.hi[a] == n[a] ? 1 : 0);
    // A partial leaf's sides are strips (solidStrips), its faces across the map squares.
    const std::int64_t strips = u == l.axis ? dv : du;
    work += faces * (partial ? (a == l.axis ? 2 * du * dv : 4 * strips) : 2 * (du + dv));
    work += partial ? (a == l.axis ? 2 * du * dv : 0) : du * dv / 16;
  }
  return work;
}

}  // namespace

double crossingMargin(const StockView& view) {
  double far = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double lo = view.origin()[a];
    far = std::max({far, std::abs(lo), std::abs(lo + view.cubes()[a] * view.spacing())});
  }
  const float f = static_cast<float>(far);
  const double step = double(std::nextafter(f, std::numeric_limits<float>::infinity())) - double(f);
  return std::clamp(kCrossingFloatSteps * step / view.spacing(), kCrossingMargin, 0.25);
}

MeshStats meshStock(const StockView& view, MeshSink& sink, const MeshOptions& options) {
  if (options.region) {
    for (int a = 0; a < 3; ++a)
      if (!(options.region->lo[a] <= options.region->hi[a]))  // also NaN
        throw std::invalid_argument(
            std::string("mesh: region box is empty or not a number along ") + "xyz"[a]);
  }
  std::vector<int> leaves;
  for (int i = 0; i < view.leafCount(); ++i)
    if (!options.region || overlaps(view.leaf(i), view, *options.region)) leaves.push_back(i);
  MeshStats stats;
  stats.brokenLeaves = view.brokenLeaves();
  const MeshRun meshRun = [&](std::span<const int> run, MeshSink& out, MeshStats& s) {
    Mesher mesher(view, out, s);
    for (int i : run) {
      ++s.leaves;
      mesher.interior(i);
      mesher.exterior(i);
    }
  };
  if (options.threads > 1 && leaves.size() > 1) {
    std::vector<std::int64_t> work;
    work.reserve(leaves.size());
    for (int i : leaves) work.push_back(workOf(view.leaf(i), view.cubes()));
    ParallelRuns runs;
    runs.threads = options.threads;
    runs.window = options.threads * std::max(1, options.runsPerThread);
    // Leaves differ a lot in cost: several runs per thread even the load out.
    runs.ends = cutRuns(work, options.runWork, 8 * static_cast<std::size_t>(options.threads));
    meshInParallel(leaves, runs, sink, stats, meshRun);
  } else
    meshRun(leaves, sink, stats);
  return stats;
}

MeshStats meshStock(const mdh::Stock& stock, MeshSink& sink, const MeshOptions& options) {
  const StockView view(stock, options.threads);
  return meshStock(view, sink, options);
}

}  // namespace mdhd::mesh

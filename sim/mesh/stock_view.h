#pragma once
// The mesher's only window on the engine (sim/mdh): the leaves of a stock and,
// for every grid vertex and grid edge, one owner leaf that answers for it.
//
// Owner rule: the grid is tiled by the leaves' half-open boxes
// [lo, hi) per axis (the grid's top plane goes to the leaf below it). A grid
// vertex, the grid edges starting at it and the grid cube whose min corner it
// is all belong to the one leaf whose half-open box holds it. Two cells that
// share a boundary plane therefore never both answer for a vertex or an edge
// on it, so the mesh of the plane is the same seen from either side.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace mdhd::mdh {
class Stock;
class ThreeMap;
}  // namespace mdhd::mdh

namespace mdhd::mesh {

using GridPoint = std::array<int, 3>;

enum class LeafKind : std::uint8_t { kSolid, kEmpty, kPartial };

struct LeafInfo {
  GridPoint lo{};
  GridPoint hi{};
  LeafKind kind = LeafKind::kSolid;
  int axis = 2;  // direction of representation (partial leaves)
  int sign = 1;
  bool twoSided = false;  // some columns hold their solid on the far side (sign -sign)
};

class StockView {
 public:
  // The stock must outlive the view and stay unchanged while it is used.
  // `threads`: how many threads index the leaves' rows of embedded heights.
  explicit StockView(const mdh::Stock& stock, int threads = 1);
  ~StockView();
  StockView(const StockView&) = delete;
  StockView& operator=(const StockView&) = delete;

  glm::dvec3 origin() const { return origin_; }
  double spacing() const { return spacing_; }        // mm between grid vertices
  const GridPoint& cubes() const { return cubes_; }  // grid cubes per axis
  int leafCount() const { return static_cast<int>(leaves_.size()); }
  const LeafInfo& leaf(int i) const { return leaves_[i].info; }

  // The leaf that owns grid vertex p (0 <= p <= cubes); `hint` is tried first.
  int ownerOf(const GridPoint& p, int hint = -1) const;
  bool owns(int leaf, const GridPoint& p) const;

  // Solidity of grid vertex p as its owner stores it.
  bool solid(const GridPoint& p, int hint = -1) const { return solidIn(ownerOf(p, hint), p); }
  // The same for a walk over neighbouring vertices: `owner` is the hint, and is
  // set to p's owner for the next one.
  bool solidWalk(const GridPoint& p, int& owner) const {
    owner = ownerOf(p, owner);
    return solidIn(owner, p);
  }
  // The same when p's owner is known.
  bool solidOwnedBy(int owner, const GridPoint& p) const { return solidIn(owner, p); }
  // The surface crossing on the grid edge from p along `axis` as its owner
  // stores it: an absolute grid coordinate. If the owner has none there
  // (cells disagree about an end), the first of the other leaves around the
  // edge (owners of the cubes beside it, in a fixed order) that has one; NaN
  // if none has.
  double crossing(const GridPoint& p, int axis, int hint = -1) const;
  // The same when p's owner is known (the mesher walking a leaf's own cubes).
  double crossingOwnedBy(int owner, const GridPoint& p, int axis) const;
  // Number of solid vertices in the column of a partial leaf through (pu, pv)
  // (grid coordinates on the leaf's u and v axes), counted from its own side.
  int columnSolidCount(int leaf, int pu, int pv) const;
  // 3-map leaves whose embedded rows did not match their parent heights (an
  // engine fault); their crossings are interpolated like a plain heightmap's.
  int brokenLeaves() const { return brokenLeaves_; }

 private:
  struct Leaf {
    LeafInfo info;
    const mdh::ThreeMap* map = nullptr;
    std::vector<int> rowStart[2];  // 3-maps: offset of each edge's embedded heights
    bool rowsBroken = false;       // embedded rows that do not match the parent heights
  };

  bool solidIn(int leaf, const GridPoint& p) const;
  double crossingIn(int leaf, const GridPoint& p, int axis) const;
  // Height h of the column through grid vertex p in partial `leaf`, or, where
  // the column is empty or full there, the height of the same column in the
  // leaves beyond along the map's axis that hold its surface: a plain map's
  // crossings interpolate between true heights even at a cell's top or bottom
  // plane (an empty column alone says only that the surface is below).
  double columnSurface(int leaf, GridPoint p, double h) const;
  static void indexRows(Leaf& leaf);
  int bucketOf(const GridPoint& p) const;

  glm::dvec3 origin_{0.0};
  double spacing_ = 1.0;
  GridPoint cubes_{};
  std::vector<Leaf> leaves_;
  int brokenLeaves_ = 0;
  // Point location: a coarse grid of buckets, each listing the leaves whose
  // owned region meets it (bucket b's are bucketLeaves_[bucketStart_[b] ..
  // bucketStart_[b + 1])).
  int bucketSize_ = 8;
  GridPoint buckets_{};
  std::vector<std::uint32_t> bucketStart_;
  std::vector<int> bucketLeaves_;
};

}  // namespace mdhd::mesh

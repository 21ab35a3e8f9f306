#pragma once
// A partial cell's surface: a (3-way) heightmap in one of six directions.
//
// Parent heights: one per column (grid line along the direction axis through
// the cell's cross-section), an absolute grid coordinate along the column, kept
// in tiles that cost nothing while all their columns are full or all empty
// (column_tiles.h). For +a the vertices k <= H are solid; for -a those with k >= H. An
// empty column stores -inf (+a) or +inf (-a), so the solid vertex count always
// follows from H alone.
//
// Embedded heights (3-maps only): between two neighbouring columns, at every
// grid level where exactly one of the two is solid, the surface crossing on
// that grid edge, again as an absolute coordinate along the edge. How many an
// edge holds follows from its two parent heights, so they are packed per row
// of edges with no index or pointer per entry.
//
// Two-sided maps (thesis 7.4: "a 3-map can store both backfacing and frontfacing
// surface portions"): a column may be flipped, its solid on the far side of its
// height (for +a: the vertices k >= H). Only columns that hold a crossing are ever
// flipped; full and empty ones keep the map's own side. Where two neighbours are on
// opposite sides the levels where exactly one is solid are up to two runs, still
// known from the two columns alone, so rows stay packed the same way.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "sim/mdh/column_tiles.h"
#include "sim/mdh/direction.h"
#include "sim/mdh/grid.h"

namespace mdhd::mdh {

// Solid vertex count of a column of height h whose levels run lo..hi, solid
// below h (up) or above it. Floor and ceiling by truncation and one compare: no
// libm call. Free so that a hot loop can keep lo, hi and up in locals.
inline int columnSolidCount(double h, int lo, int hi, bool up) {
  if (up) {
    if (!(h >= lo)) return 0;  // -inf and NaN too
    if (h >= hi) return hi - lo + 1;
    const int f = static_cast<int>(h);  // truncation: the floor unless h < 0
    return (f > h ? f - 1 : f) - lo + 1;
  }
  if (!(h <= hi)) return h != h ? hi - lo + 1 : 0;
  if (h <= lo) return hi - lo + 1;
  const int c = static_cast<int>(h);
  return hi - (c < h ? c + 1 : c) + 1;
}

// The levels where two columns with solid counts f1 and f2 differ: first, first+1, ... (count).
inline void columnStraddle(int f1, int f2, int lo, int hi, bool up, int& first, int& count) {
  count = f1 > f2 ? f1 - f2 : f2 - f1;
  first = up ? lo + std::min(f1, f2) : hi - std::max(f1, f2) + 1;
}

// The levels where two columns differ, ascending: one run when the columns are on
// the same side, up to two when they are not.
struct ColumnStraddle {
  int first[2] = {0, 0};
  int count[2] = {0, 0};
  int total() const { return count[0] + count[1]; }
  // Position of `level` among the straddled levels, or -1.
  int indexOf(int level) const {
    if (level >= first[0] && level < first[0] + count[0]) return level - first[0];
    if (level >= first[1] && level < first[1] + count[1]) return count[0] + level - first[1];
    return -1;
  }
  int level(int i) const { return i < count[0] ? first[0] + i : first[1] + i - count[0]; }
};

// Columns with solid counts f0, f1 on sides up0, up1 (solid from the low face or
// from the high one), levels lo..hi.
inline ColumnStraddle columnsStraddle(int f0, bool up0, int f1, bool up1, int lo, int hi) {
  ColumnStraddle s;
  if (up0 == up1) {
    columnStraddle(f0, f1, lo, hi, up0, s.first[0], s.count[0]);
    return s;
  }
  const int n = hi - lo + 1;
  const int fu = up0 ? f0 : f1, fd = up0 ? f1 : f0;  // the up column's count, the down one's
  s.count[0] = std::min(fu, n - fd);                 // low levels: only the up one solid
  s.first[0] = lo;
  s.count[1] = std::min(fd, n - fu);  // high levels: only the down one solid
  s.first[1] = hi - s.count[1] + 1;
  if (s.count[0] == 0) {
    s.first[0] = s.first[1];
    s.count[0] = s.count[1];
    s.count[1] = 0;
  }
  return s;
}

class ThreeMap {
 public:
  // All columns full.
  ThreeMap(const GridBox& box, Direction dir, bool threeWay);

  const GridBox& box() const { return box_; }
  Direction direction() const { return dir_; }
  bool threeWay() const { return threeWay_; }
  int axis() const { return dir_.axis; }
  int uAxis() const { return axisU(dir_.axis); }
  int vAxis() const { return axisV(dir_.axis); }
  int columnsU() const { return nu_; }
  int columnsV() const { return nv_; }
  int levels() const { return box_.points(dir_.axis); }

  double height(int iu, int iv) const { return columns_.get(iu, iv); }
  // The parent heights for hot loops: valid until the next setHeight / setColumn.
  TileReader heights() const { return columns_.reader(); }
  // The parent heights of columns [e0, e1) of a row (rowHeight's order) into out.
  void rowHeights(int family, int index, int e0, int e1, double* out) const {
    if (family == 0)
      columns_.copyRow(index, e0, e1, out);
    else
      columns_.copyColumn(index, e0, e1, out);
  }
  // Columns [0, n) of a row: heights, sides (1: solid from the low face) and solid
  // counts, read out of the tiles once.
  void rowColumns(int family, int index, int n, double* heights, std::uint8_t* ups,
                  int* counts) const;
  // solidCount(height) of every column, row-major (iv * columnsU() + iu): a map
  // without flips, its columns' solid counts.
  void solidCounts(int* out) const {
    // Locals: through `this` each store into out would reload the box.
    const int lo = box_.lo[dir_.axis], hi = box_.hi[dir_.axis];
    const bool up = dir_.sign > 0;
    columns_.forEachRowMajor(out,
                             [lo, hi, up](double h) { return columnSolidCount(h, lo, hi, up); });
  }
  // An unflipped column (a flipped one loses its flip).
  void setHeight(int iu, int iv, double h) {
    if (flipped(iu, iv)) {
      setColumn(iu, iv, h, false);
      return;
    }
    setHeight(iu, iv, h, solidCount(height(iu, iv)), solidCount(h));
  }
  // Two-sided maps: a column's height and side (`flip`: solid on the far side). A
  // full or empty column is stored unflipped.
  void setColumn(int iu, int iv, double h, bool flip);
  bool hasFlips() const { return flips_ > 0; }
  int flippedColumns() const { return flips_; }
  bool flipped(int iu, int iv) const { return flips_ > 0 && columns_.flipped(iu, iv); }
  // A column's height and whether its solid runs from the low face (the +a side), in
  // one look-up.
  double column(int iu, int iv, bool& up) const {
    bool flip = false;
    const double h = columns_.column(iu, iv, flips_ > 0, flip);
    up = (dir_.sign > 0) != flip;
    return h;
  }
  bool columnUp(int iu, int iv) const { return (dir_.sign > 0) != flipped(iu, iv); }
  // The column's solid vertex count, solidity at a level and solid length, whatever
  // its side (the h-only forms below hold for unflipped columns).
  int columnCount(int iu, int iv) const {
    bool up = false;
    const double h = column(iu, iv, up);
    return columnSolidCount(h, box_.lo[dir_.axis], box_.hi[dir_.axis], up);
  }
  bool columnSolidAt(int iu, int iv, int level) const {
    bool up = false;
    const double h = column(iu, iv, up);
    return up ? level <= h : level >= h;
  }
  double columnLengthAt(int iu, int iv) const {
    bool up = false;
    const double h = column(iu, iv, up);
    return lengthOf(h, up);
  }
  // The levels where two neighbouring columns differ (their edges' crossings).
  ColumnStraddle straddleColumns(int iu0, int iv0, int iu1, int iv1) const {
    const int lo = box_.lo[dir_.axis], hi = box_.hi[dir_.axis];
    bool up0 = false, up1 = false;
    const double h0 = column(iu0, iv0, up0), h1 = column(iu1, iv1, up1);
    return columnsStraddle(columnSolidCount(h0, lo, hi, up0), up0,
                           columnSolidCount(h1, lo, hi, up1), up1, lo, hi);
  }
  // The same for edge `edge` of a row (rowHeight's columns).
  ColumnStraddle straddleEdge(int family, int index, int edge) const {
    return family == 0 ? straddleColumns(edge, index, edge + 1, index)
                       : straddleColumns(index, edge, index, edge + 1);
  }
  // The same when the caller has the solid counts before and after (a cut does).
  void setHeight(int iu, int iv, double h, int countBefore, int countAfter) {
    store(iu, iv, h, false, countBefore, countAfter);
  }
  double emptyHeight() const { return dir_.sign > 0 ? -kInf : kInf; }
  double fullHeight() const { return dir_.sign > 0 ? box_.hi[dir_.axis] : box_.lo[dir_.axis]; }

  // Number of solid vertices of a column with height h (inline: the hottest call).
  int solidCount(double h) const {
    return columnSolidCount(h, box_.lo[dir_.axis], box_.hi[dir_.axis], dir_.sign > 0);
  }
  bool solidAt(double h, int level) const { return dir_.sign > 0 ? level <= h : level >= h; }
  // The grid levels where columns h1 and h2 differ: first, first+1, ... (count).
  void straddle(double h1, double h2, int& first, int& count) const;
  // The same from the two columns' solid counts (a caller that has them already).
  void straddleCounts(int f1, int f2, int& first, int& count) const {
    columnStraddle(f1, f2, box_.lo[dir_.axis], box_.hi[dir_.axis], dir_.sign > 0, first, count);
  }
  // Solid length of a column in grid units.
  double columnLength(double h) const { return lengthOf(h, dir_.sign > 0); }
  double lengthOf(double h, bool up) const {
    const double lo = box_.lo[dir_.axis], hi = box_.hi[dir_.axis];
    if (up) return h < lo ? 0.0 : std::min(h, hi) - lo;
    return h > hi ? 0.0 : hi - std::max(h, lo);
  }

  // Embedded heights. family 0: edges along u, row index = iv; family 1: edges
  // along v, row index = iu. Entries: edge by edge, levels ascending.
  const std::vector<double>& row(int family, int index) const { return rows_[family][index]; }
  std::vector<double>& row(int family, int index) { return rows_[family][index]; }
  int rowCount(int family) const { return family == 0 ? nv_ : nu_; }
  int edgesInRow(int family) const { return family == 0 ? nu_ - 1 : nv_ - 1; }
  // Parent height of the column at position e (0 or 1 side) of edge `edge` in a row.
  double rowHeight(int family, int index, int edge) const {
    return family == 0 ? height(edge, index) : height(index, edge);
  }
  // The embedded crossing on edge `edge` of row `index` (family as row()) at grid
  // `level`, an absolute coordinate along the edge; NaN where the edge holds none
  // there, in a plain heightmap, or where the row is not packed as its columns say.
  // Walks the row from its start (rows have no index): for queries, not cuts.
  double edgeCrossing(int family, int index, int edge, int level) const;
  // The crossing on an edge at `level` when no embedded heights are stored:
  // linear interpolation between the two parent heights.
  double interpolatedCrossing(double h0, double h1, int edgeStart, int level) const;

  // Volume in grid units^3: per grid square, the integral of the Coons patch
  // through its four edge profiles (1/2 the sum of the edge integrals minus
  // 1/4 the sum of the corner heights). An edge profile runs through the two
  // parent heights and, in a 3-map, the embedded crossings, so a face lying
  // on a grid plane is exact whatever the direction; a plain heightmap gets
  // the bilinear (trapezoid) value.
  double volume() const { return squaresVolume(0, nu_ - 1, 0, nv_ - 1); }
  // The same over the squares whose corners lie in columns [iu0, iu1] x [iv0, iv1].
  double squaresVolume(int iu0, int iu1, int iv0, int iv1) const;
  // The part of squaresVolume that reads a corner where a surface passes exactly
  // through the column (a tool tangent to the grid line, a pocket's corner on it):
  // the column is lowered, but the profiles of both of a square's edges leaving it
  // jump at once back to their crossings, and the Coons patch would bulge by a
  // quarter of the drop (a tool tangent to a face added material). Such a corner
  // is read at the mean of the two profiles' ends instead; a corner that agrees
  // with either edge (a wall on a grid plane) keeps its column, which keeps the
  // patch exact there.
  double cornerCorrection(int iu0, int iu1, int iv0, int iv1) const;
  // The integral of one edge's profile: between columns of heights h0 and h1,
  // the edge starting at grid coordinate edgeStart, with its straddle(h0, h1)
  // embedded crossings at `crossings` (ignored in a plain heightmap).
  double edgeIntegral(double h0, double h1, int edgeStart, const double* crossings) const;
  // How many grid squares hold an edge of row `index` (family 0: rows along u)
  // and a column: the weights of their terms in volume() (1/2 and 1/4 each),
  // so a change of a few edges and columns is a volume change of a few terms.
  int squaresAtEdge(int family, int index) const {
    const int n = family == 0 ? nv_ : nu_;
    return (index > 0) + (index < n - 1);
  }
  int squaresAtColumn(int iu, int iv) const {
    return ((iu > 0) + (iu < nu_ - 1)) * ((iv > 0) + (iv < nv_ - 1));
  }
  double columnWeight(int iu, int iv) const {
    return ((iu == 0 || iu == nu_ - 1) && nu_ > 1 ? 0.5 : 1.0) *
           ((iv == 0 || iv == nv_ - 1) && nv_ > 1 ? 0.5 : 1.0);
  }
  // Around filling every column of a new map (a split's child, an encode): one
  // allocation for the heights, trimmed to the tiles stored afterwards.
  void reserveAllColumns() { columns_.reserveAll(); }
  void releaseSlack() { columns_.releaseSlack(); }
  bool allFull() const { return fullColumns_ == nu_ * nv_; }
  bool allEmpty() const { return emptyColumns_ == nu_ * nv_; }
  std::size_t memoryBytes() const;
  std::size_t embeddedCount() const;

  // The same surface restricted to a sub-box (used when a cell is split).
  ThreeMap restrictedTo(const GridBox& sub) const;

 private:
  // Stores a column, keeping the full and empty column counts.
  void store(int iu, int iv, double h, bool flip, int countBefore, int countAfter) {
    const int n = levels();
    fullColumns_ += (countAfter == n) - (countBefore == n);
    emptyColumns_ += (countAfter == 0) - (countBefore == 0);
    columns_.set(iu, iv, h, flip);
  }
  double profileIntegral(int f0, int f1, double len0, double len1, int edgeStart,
                         const double* crossings, bool up) const;
  // The profile's values just inside its ends (at 0+ and 1-) into ends[0], ends[1],
  // kAgrees where that is the column's own length (no crossing on that end).
  void profileEnds(int f0, int f1, double len0, double len1, int edgeStart, const double* crossings,
                   bool up, double* ends) const;
  static constexpr double kAgrees = std::numeric_limits<double>::quiet_NaN();
  // Per-thread room for the ends of the edges of nu x nv squares (row by row, two per
  // edge: the u edges' rows then the v edges').
  static void cornerScratch(int nu, int nv, double*& endsU, double*& endsV);
  // The correction from the ends of every edge of the squares in [iu0, iu1] x [iv0, iv1].
  double cornerSum(int iu0, int iu1, int iv0, int iv1, const double* endsU,
                   const double* endsV) const;
  double mixedEdgeIntegral(int f0, int f1, double len0, double len1, bool up0, int edgeStart,
                           const double* crossings) const;

  GridBox box_;
  Direction dir_;
  bool threeWay_;
  int nu_;
  int nv_;
  int fullColumns_;
  int emptyColumns_ = 0;
  ColumnTiles columns_;  // parent heights and sides
  std::vector<std::vector<double>> rows_[2];
  int flips_ = 0;
};

}  // namespace mdhd::mdh

#pragma once
// A 3-map's parent heights and column sides, stored in square tiles of up to 8 x 8
// columns. A tile whose columns are all full (or all empty), unflipped and at the
// map's canonical full (empty) height holds no storage: it is one slot entry.
//
// Why: thesis 6.3 finds its largest waste in null grid entries (a pointer per
// column that holds no sample). Dense parent heights pay 8 bytes for each such
// column; in a large cell most columns are untouched stock or cut through. A tile
// materializes at its first column that differs and is released when its last
// column becomes canonical again, so memory follows the surface, not the face.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mdhd::mdh {

// Read access in hot loops: raw pointers, valid until the next store into the tiles.
// Tiles are 1 << shift columns wide and tall but for the last tile of a row (and the
// last row of tiles), which holds only the map's remaining columns: a brick's map of
// 33 x 33 columns stores 33 x 33 heights, not 40 x 40.
struct TileReader {
  const std::int32_t* slot;  // per tile: its first height in the pool, or uniform
  const double* pool;
  int tilesU;
  int shiftU, shiftV;  // tile extent 1 << shift along u and v
  int lastWidth;       // columns of the last tile of a row of tiles
  double uniform[2];   // the height of a uniform tile: [0] empty, [1] full

  static constexpr std::int32_t kEmptyTile = -1;
  static constexpr std::int32_t kFullTile = -2;

  int tileOf(int iu, int iv) const { return (iv >> shiftV) * tilesU + (iu >> shiftU); }
  int widthOf(int iu) const { return (iu >> shiftU) == tilesU - 1 ? lastWidth : 1 << shiftU; }
  std::size_t offsetIn(std::int32_t s, int iu, int iv) const {
    return static_cast<std::size_t>(s) +
           static_cast<std::size_t>((iv & ((1 << shiftV) - 1)) * widthOf(iu) +
                                    (iu & ((1 << shiftU) - 1)));
  }
  double get(int iu, int iv) const {
    const std::int32_t s = slot[tileOf(iu, iv)];
    return s >= 0 ? pool[offsetIn(s, iu, iv)] : uniform[s == kFullTile];
  }
};

class ColumnTiles {
 public:
  ColumnTiles() = default;
  // nu x nv columns, all full (height `full`); an empty column's height is `empty`.
  ColumnTiles(int nu, int nv, double full, double empty);

  double get(int iu, int iv) const { return reader().get(iu, iv); }
  bool flipped(int iu, int iv) const {
    bool flip = false;
    column(iu, iv, !flipPool_.empty(), flip);
    return flip;
  }
  // A column's height and, when the tiles may hold flips (`anyFlips`), its side.
  double column(int iu, int iv, bool anyFlips, bool& flip) const {
    const TileReader r = reader();
    const std::int32_t s = slot_[r.tileOf(iu, iv)];
    if (s < 0) {
      flip = false;
      return uniform_[s == TileReader::kFullTile];
    }
    const std::size_t i = r.offsetIn(s, iu, iv);
    flip = anyFlips && flipPool_[i] != 0;
    return pool_[i];
  }
  // Stores a column's height and side. A full or empty column is canonical (no storage
  // needed) only at exactly the full or empty height and unflipped.
  void set(int iu, int iv, double h, bool flip) {
    const int tile = reader().tileOf(iu, iv);
    const std::int32_t s = slot_[tile];
    if (s < 0 && !flip && h == uniform_[s == TileReader::kFullTile]) return;
    setSlow(tile, iu, iv, h, flip);
  }
  TileReader reader() const {
    return {slot_.data(),
            pool_.data(),
            tilesU_,
            shiftU_,
            shiftV_,
            lastWidth_,
            {uniform_[0], uniform_[1]}};
  }
  // Heights of columns [iu0, iu1) of row iv, or of rows [iv0, iv1) of column iu, into out.
  void copyRow(int iv, int iu0, int iu1, double* out) const { copyLine<true>(iv, iu0, iu1, out); }
  void copyColumn(int iu, int iv0, int iv1, double* out) const {
    copyLine<false>(iu, iv0, iv1, out);
  }
  // f(h) for every column, row-major into out (nu * nv entries): per uniform tile, once.
  template <class F>
  void forEachRowMajor(int* out, F f) const;

  // Building a whole map column by column: room for every column at once, then only
  // what the stored tiles use (a pool grown a quarter at a time would be copied
  // some 20 times on the way to a large cell's size).
  void reserveAll() { pool_.reserve(static_cast<std::size_t>(nu_) * nv_); }
  void releaseSlack() {
    pool_.shrink_to_fit();
    flipPool_.shrink_to_fit();
  }

  int materializedTiles() const { return static_cast<int>(slot_.size()) - uniformTiles_; }
  std::size_t memoryBytes() const;

 private:
  void setSlow(int tile, int iu, int iv, double h, bool flip);
  template <bool alongU>
  void copyLine(int fixed, int from, int to, double* out) const;
  // A tile's size class (last of its row of tiles, in the last row: 0..3) and columns.
  int tileClass(int tile) const {
    return (tile % tilesU_ == tilesU_ - 1) + 2 * (tile / tilesU_ == tilesV_ - 1);
  }
  int tileColumns(int tile) const { return classColumns_[tileClass(tile)]; }
  // 0: empty canonical, 1: full canonical, 2: anything else.
  int kindOf(double h, bool flip) const {
    return flip ? 2 : h == uniform_[0] ? 0 : h == uniform_[1] ? 1 : 2;
  }

  int nu_ = 0, nv_ = 0, tilesU_ = 0, tilesV_ = 0;
  int shiftU_ = 0, shiftV_ = 0, lastWidth_ = 0;
  int classColumns_[4] = {0, 0, 0, 0};
  double uniform_[2] = {0.0, 0.0};
  int uniformTiles_ = 0;
  std::vector<std::int32_t> slot_;
  std::vector<double> pool_;
  std::vector<std::uint8_t> flipPool_;      // parallel to pool_, from the first flip
  std::vector<std::uint8_t> canonical_[2];  // per tile: its empty / full columns
  std::vector<std::int32_t> free_[4];       // released slots, by size class
};

template <class F>
void ColumnTiles::forEachRowMajor(int* out, F f) const {
  const int tu = 1 << shiftU_, tv = 1 << shiftV_;
  const int uniformValue[2] = {f(uniform_[0]), f(uniform_[1])};
  for (int t = 0; t < tilesV_; ++t) {
    const std::int32_t* slots = slot_.data() + static_cast<std::size_t>(t) * tilesU_;
    const int iv0 = t * tv, iv1 = std::min(nv_, iv0 + tv);
    for (int iv = iv0; iv < iv1; ++iv) {
      int* row = out + static_cast<std::size_t>(iv) * nu_;
      for (int s = 0; s < tilesU_; ++s, row += tu) {
        const std::int32_t k = slots[s];
        const int width = s == tilesU_ - 1 ? lastWidth_ : tu;
        if (k < 0) {
          std::fill_n(row, width, uniformValue[k == TileReader::kFullTile]);
          continue;
        }
        const double* p = pool_.data() + k + static_cast<std::size_t>(iv - iv0) * width;
        for (int i = 0; i < width; ++i) row[i] = f(p[i]);
      }
    }
  }
}

}  // namespace mdhd::mdh

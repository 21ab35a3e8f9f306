#include "sim/mdh/column_tiles.h"

namespace mdhd::mdh {

namespace {

// The smallest shift with 1 << shift >= n, at most 3 (8 columns): a thin map's tiles
// are no wider than the map.
int tileShift(int n) {
  int s = 0;
  while (s < 3 && (1 << s) < n) ++s;
  return s;
}

}  // namespace

ColumnTiles::ColumnTiles(int nu, int nv, double full, double empty)
    : nu_(nu), nv_(nv), shiftU_(tileShift(nu)), shiftV_(tileShift(nv)), uniform_{empty, full} {
  const int tu = 1 << shiftU_, tv = 1 << shiftV_;
  tilesU_ = (nu + tu - 1) >> shiftU_;
  tilesV_ = (nv + tv - 1) >> shiftV_;
  lastWidth_ = nu - (tilesU_ - 1) * tu;
  const int lastHeight = nv - (tilesV_ - 1) * tv;
  // A map one tile wide has its only tile in class 1 (last of its row): its width.
  classColumns_[0] = tu * tv;
  classColumns_[1] = lastWidth_ * tv;
  classColumns_[2] = tu * lastHeight;
  classColumns_[3] = lastWidth_ * lastHeight;
  slot_.assign(static_cast<std::size_t>(tilesU_) * tilesV_, TileReader::kFullTile);
  canonical_[0].assign(slot_.size(), 0);
  canonical_[1].assign(slot_.size(), 0);
  uniformTiles_ = static_cast<int>(slot_.size());
}

void ColumnTiles::setSlow(int tile, int iu, int iv, double h, bool flip) {
  std::int32_t s = slot_[tile];
  if (s < 0) {  // materialize: every column at the tile's uniform height
    const int kind = s == TileReader::kFullTile;
    const int c = tileClass(tile);
    const std::size_t size = static_cast<std::size_t>(classColumns_[c]);
    if (!free_[c].empty()) {
      s = free_[c].back();
      free_[c].pop_back();
    } else {
      s = static_cast<std::int32_t>(pool_.size());
      // Grow by a quarter (at least 4 tiles), not double: the pool is most of a map's
      // memory. It never holds more than the map's columns.
      if (pool_.size() + size > pool_.capacity()) {
        const std::size_t all = static_cast<std::size_t>(nu_) * nv_;
        const std::size_t grow = std::max<std::size_t>(4 * classColumns_[0], pool_.size() / 4);
        pool_.reserve(std::max(pool_.size() + size, std::min(all, pool_.size() + grow)));
      }
      pool_.resize(pool_.size() + size);
      if (!flipPool_.empty()) {
        if (flipPool_.capacity() < pool_.capacity()) flipPool_.reserve(pool_.capacity());
        flipPool_.resize(pool_.size(), 0);
      }
    }
    std::fill_n(pool_.begin() + s, size, uniform_[kind]);
    canonical_[kind][tile] = static_cast<std::uint8_t>(size);
    canonical_[1 - kind][tile] = 0;
    slot_[tile] = s;
    --uniformTiles_;
  }
  const TileReader r = reader();
  const std::size_t i = r.offsetIn(s, iu, iv);
  const bool wasFlipped = !flipPool_.empty() && flipPool_[i] != 0;
  const int before = kindOf(pool_[i], wasFlipped), after = kindOf(h, flip);
  pool_[i] = h;
  if (flip != wasFlipped) {
    if (flipPool_.empty()) {
      flipPool_.reserve(pool_.capacity());
      flipPool_.assign(pool_.size(), 0);
    }
    flipPool_[i] = flip ? 1 : 0;
  }
  if (before == after) return;
  if (before < 2) --canonical_[before][tile];
  if (after < 2 && ++canonical_[after][tile] == tileColumns(tile)) {
    // Every column canonical and unflipped: back to one slot entry.
    slot_[tile] = after == 1 ? TileReader::kFullTile : TileReader::kEmptyTile;
    free_[tileClass(tile)].push_back(s);
    ++uniformTiles_;
  }
}

template <bool alongU>
void ColumnTiles::copyLine(int fixed, int from, int to, double* out) const {
  const TileReader r = reader();
  const int shift = alongU ? shiftU_ : shiftV_;
  // Within a tile a row is contiguous; a column steps by the tile's width.
  const std::ptrdiff_t step = alongU ? 1 : r.widthOf(fixed);  // 1: a copy the compiler sees
  for (int k = from; k < to;) {
    const int end = std::min(to, ((k >> shift) + 1) << shift);  // this tile's part
    const int iu = alongU ? k : fixed, iv = alongU ? fixed : k;
    const std::int32_t s = slot_[r.tileOf(iu, iv)];
    if (s < 0) {
      std::fill(out, out + (end - k), uniform_[s == TileReader::kFullTile]);
    } else {
      const double* p = r.pool + r.offsetIn(s, iu, iv);
      for (int i = 0; i < end - k; ++i) out[i] = p[i * step];
    }
    out += end - k;
    k = end;
  }
}

template void ColumnTiles::copyLine<true>(int, int, int, double*) const;
template void ColumnTiles::copyLine<false>(int, int, int, double*) const;

std::size_t ColumnTiles::memoryBytes() const {
  std::size_t bytes = slot_.capacity() * sizeof(std::int32_t) + pool_.capacity() * sizeof(double) +
                      flipPool_.capacity() + canonical_[0].capacity() + canonical_[1].capacity();
  for (const auto& f : free_) bytes += f.capacity() * sizeof(std::int32_t);
  return bytes;
}

}  // namespace mdhd::mdh

// Parent heights in tiles: storage only where a tile's columns are not all full or
// all empty, and reads identical to a dense array whatever the writes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sim/mdh/column_tiles.h"
#include "sim/mdh/three_map.h"

namespace mdhd::mdh {
namespace {

constexpr double kFull = 40.0;
constexpr double kEmpty = -std::numeric_limits<double>::infinity();

TEST(ColumnTiles, StartFullWithNoStorage) {
  ColumnTiles t(21, 13, kFull, kEmpty);
  EXPECT_EQ(t.materializedTiles(), 0);
  EXPECT_EQ(t.get(20, 12), kFull);
  EXPECT_FALSE(t.flipped(3, 4));
  // 3 x 2 tiles of up to 8 x 8: a slot and two counts each, no pool.
  EXPECT_EQ(t.memoryBytes(), 6 * (sizeof(std::int32_t) + 2));
}

TEST(ColumnTiles, ATileMaterializesAtItsFirstDifferentColumnAndIsReleasedWhenUniform) {
  ColumnTiles t(21, 13, kFull, kEmpty);
  t.set(9, 2, kFull, false);  // the uniform value: nothing stored
  EXPECT_EQ(t.materializedTiles(), 0);
  t.set(9, 2, 31.5, false);
  EXPECT_EQ(t.materializedTiles(), 1);
  EXPECT_EQ(t.get(9, 2), 31.5);
  EXPECT_EQ(t.get(8, 2), kFull);  // the tile's other columns keep the uniform height
  EXPECT_EQ(t.get(7, 2), kFull);  // another tile
  // Cut the whole tile (columns 8..15 x 0..7) through: back to one slot entry.
  for (int iv = 0; iv < 8; ++iv)
    for (int iu = 8; iu < 16; ++iu) t.set(iu, iv, kEmpty, false);
  EXPECT_EQ(t.materializedTiles(), 0);
  EXPECT_EQ(t.get(9, 2), kEmpty);
  // A released slot is reused, filled with the new tile's uniform height.
  t.set(0, 0, 12.0, false);
  EXPECT_EQ(t.materializedTiles(), 1);
  EXPECT_EQ(t.get(1, 1), kFull);
  EXPECT_EQ(t.get(0, 0), 12.0);
}

TEST(ColumnTiles, EdgeTilesCountOnlyTheirColumns) {
  // Columns 16..20 x 8..12 form the corner tile: 5 x 5 columns, 25 heights.
  ColumnTiles t(21, 13, kFull, kEmpty);
  for (int iv = 8; iv < 13; ++iv)
    for (int iu = 16; iu < 21; ++iu) t.set(iu, iv, 5.0, false);
  EXPECT_EQ(t.materializedTiles(), 1);
  EXPECT_EQ(t.get(16, 8), 5.0);
  EXPECT_EQ(t.get(15, 8), kFull);
  for (int iv = 8; iv < 13; ++iv)
    for (int iu = 16; iu < 21; ++iu) t.set(iu, iv, kEmpty, false);
  EXPECT_EQ(t.materializedTiles(), 0);
}

TEST(ColumnTiles, AFlippedColumnAtTheFullHeightIsNotUniform) {
  // For +a a flipped column of height `full` holds one solid vertex: it needs storage.
  ColumnTiles t(4, 4, kFull, kEmpty);
  t.set(1, 1, kFull, true);
  EXPECT_EQ(t.materializedTiles(), 1);
  EXPECT_TRUE(t.flipped(1, 1));
  EXPECT_FALSE(t.flipped(1, 2));
  t.set(1, 1, kFull, false);
  EXPECT_EQ(t.materializedTiles(), 0);
  EXPECT_FALSE(t.flipped(1, 1));
}

TEST(ColumnTiles, ThinMapsGetThinTiles) {
  // A 3 x 40 face: tiles 3 x 8. The pool reserves room for a few tiles at a time,
  // never more than the map's 120 columns; a full one holds exactly those.
  ColumnTiles t(3, 40, kFull, kEmpty);
  t.set(2, 39, 1.0, false);
  EXPECT_EQ(t.materializedTiles(), 1);
  EXPECT_LE(t.memoryBytes(), 120 * sizeof(double) + 5 * (sizeof(std::int32_t) + 2));
  for (int iv = 0; iv < 40; ++iv)
    for (int iu = 0; iu < 3; ++iu) t.set(iu, iv, 2.0, false);
  EXPECT_EQ(t.memoryBytes(), 120 * sizeof(double) + 5 * (sizeof(std::int32_t) + 2));
}

TEST(ColumnTiles, RandomWritesReadLikeADenseArray) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const int nu = 1 + int(rng() % 30), nv = 1 + int(rng() % 30);
    ColumnTiles t(nu, nv, kFull, kEmpty);
    std::vector<double> dense(std::size_t(nu) * nv, kFull);
    std::vector<char> flips(dense.size(), 0);
    const double values[] = {kFull, kEmpty, 3.25, 17.0, kFull + 1};
    for (int k = 0; k < 2000; ++k) {
      const int iu = int(rng() % nu), iv = int(rng() % nv);
      const double h = values[rng() % 5];
      const bool flip = h != kFull && h != kEmpty && rng() % 3 == 0;
      t.set(iu, iv, h, flip);
      dense[std::size_t(iv) * nu + iu] = h;
      flips[std::size_t(iv) * nu + iu] = flip;
    }
    std::vector<int> viaTiles(dense.size());
    t.forEachRowMajor(viaTiles.data(), [](double h) { return int(std::floor(h * 4)); });
    int stored = 0;
    for (int iv = 0; iv < nv; ++iv)
      for (int iu = 0; iu < nu; ++iu) {
        const std::size_t i = std::size_t(iv) * nu + iu;
        ASSERT_EQ(t.get(iu, iv), dense[i]) << nu << "x" << nv << " " << iu << "," << iv;
        ASSERT_EQ(t.flipped(iu, iv), flips[i] != 0);
        ASSERT_EQ(viaTiles[i], int(std::floor(dense[i] * 4)));
        stored += dense[i] != kFull && dense[i] != kEmpty;
      }
    // Every tile holding a column off the two canonical heights is stored, no more
    // tiles than columns written, and a map cut through entirely holds none.
    EXPECT_LE(stored > 0 ? 1 : 0, t.materializedTiles());
    for (int iv = 0; iv < nv; ++iv)
      for (int iu = 0; iu < nu; ++iu) t.set(iu, iv, kEmpty, false);
    EXPECT_EQ(t.materializedTiles(), 0);
  }
}

TEST(ColumnTiles, AMapsSolidCountsComeFromItsTiles) {
  ThreeMap m({{0, 0, 0}, {20, 11, 9}}, Direction{2, +1}, true);
  m.setHeight(3, 4, 4.5);
  m.setHeight(19, 10, -std::numeric_limits<double>::infinity());
  std::vector<int> counts(std::size_t(m.columnsU()) * m.columnsV());
  m.solidCounts(counts.data());
  for (int iv = 0; iv < m.columnsV(); ++iv)
    for (int iu = 0; iu < m.columnsU(); ++iu)
      EXPECT_EQ(counts[std::size_t(iv) * m.columnsU() + iu], m.columnCount(iu, iv));
  EXPECT_EQ(counts[4 * 21 + 3], 5);
  EXPECT_EQ(counts[10 * 21 + 19], 0);
}

}  // namespace
}  // namespace mdhd::mdh

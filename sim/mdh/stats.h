#pragma once
// What the stock reports about itself (job report section 5, `mdh` block).
#include <array>
#include <cstddef>
#include <cstdint>

namespace mdhd::mdh {

struct Stats {
  std::int64_t cells = 0;  // tree nodes, bricks' roots included
  std::int64_t leaves = 0;
  std::array<std::int64_t, 6> directions{};  // partial leaves by +x -x +y -y +z -z
  std::int64_t solid = 0;
  std::int64_t empty = 0;
  std::int64_t splitsDirect = 0;
  std::int64_t splitsIndirect = 0;
  std::int64_t splitsSignConflict = 0;
  std::int64_t splitsFallback = 0;  // not in the thesis: sub-grid features
  std::int64_t overhangEvents = 0;
  std::int64_t resamples = 0;
  std::int64_t forcedCells = 0;
  std::int64_t forcedVertices = 0;
  std::int64_t flippedColumns = 0;   // two-sided maps' columns solid on the far side
  std::int64_t twoSidedLeaves = 0;   // leaves holding some
  std::int64_t parentSamples = 0;    // parent heights strictly inside their cell
  std::int64_t embeddedSamples = 0;  // embedded heights stored
  std::size_t memoryBytes = 0;       // everything the stock allocated
  double pointerGridBytes = 0.0;     // the 3D pointer grid of thesis 6.3, same surface
  double pointerGridPercent = 0.0;
  std::int64_t splits() const {
    return splitsDirect + splitsIndirect + splitsSignConflict + splitsFallback;
  }
};

}  // namespace mdhd::mdh

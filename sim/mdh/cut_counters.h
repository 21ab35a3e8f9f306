#pragma once
// What one cut did, counted per brick so parallel work merges in a fixed order.
#include <array>
#include <cstdint>
#include <vector>

#include "sim/mdh/split_candidate.h"

namespace mdhd::mdh {

struct CutCounters {
  std::array<std::int64_t, kSplitTypes> splits{};  // by SplitType
  std::int64_t overhangEvents = 0;                 // a cell became non-functional for its direction
  std::int64_t resamples = 0;                      // ... and took a new direction without splitting
  std::int64_t forcedCells = 0;  // unsplittable cells made functional by dropping vertices
  std::int64_t forcedVertices = 0;
  // Leaves that took the slow path (unpacked): overhang events, and two-sided cells'
  // cuts that kept their direction (no event).
  std::int64_t slowCuts = 0;
  double removed = 0.0;  // grid units^3
  bool touched = false;
  // Surely changed: touched, but in a z map only where a column moved (a lazy cut
  // cannot tell whether it moved a crossing until it is settled).
  bool removes = false;
  // Vertices forced cells dropped: the other cells holding them drop them too
  // (Stock::cut, vertex_drops.h).
  std::vector<std::array<int, 3>> dropped;

  void add(const CutCounters& o) {
    for (int i = 0; i < kSplitTypes; ++i) splits[i] += o.splits[i];
    overhangEvents += o.overhangEvents;
    resamples += o.resamples;
    forcedCells += o.forcedCells;
    forcedVertices += o.forcedVertices;
    slowCuts += o.slowCuts;
    removed += o.removed;
    touched |= o.touched;
    removes = removes || o.removes;
    dropped.insert(dropped.end(), o.dropped.begin(), o.dropped.end());
  }
};

}  // namespace mdhd::mdh

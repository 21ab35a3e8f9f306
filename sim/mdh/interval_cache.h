#pragma once
// The tool's intervals for one in-between step, along every grid line its
// bounds reach, in grid units. Each line is computed once, on first use, by
// whichever thread gets there first, and then shared by every cell: only the
// lines a cut really asks for cost a LineSolid query (thesis 5.2.2 asked for
// the lines' extents only; this asks for the lines themselves only).
//
// The slots live in a LineStore that the stock keeps from step to step, so a
// step allocates nothing once the store has grown to the largest tool box; a
// slot is "filled" when its stamp is this step's, so nothing is cleared either.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "sim/geometry/line_solid.h"
#include "sim/mdh/grid.h"
#include "sim/mdh/line_segments.h"

namespace mdhd::mdh {

class LineStore {
 public:
  LineStore();
  ~LineStore();
  LineStore(const LineStore&) = delete;
  LineStore& operator=(const LineStore&) = delete;

 private:
  friend class IntervalCache;
  struct Slot;
  // Makes room for n slots and returns the stamp that marks this step's filled ones.
  std::uint32_t begin(std::size_t n);

  std::unique_ptr<Slot[]> slots_;
  std::size_t capacity_ = 0;
  std::uint32_t stamp_ = 0;
  std::mutex overflowMutex_;
  std::vector<std::unique_ptr<Span[]>> overflow_;  // lines with more intervals than a slot holds
};

class IntervalCache {
 public:
  // `store` (may be null: the cache then owns one) must outlive the cache and
  // serve one cache at a time. `axes`: bit a set = lines along axis a may be
  // asked for (a probe needs only z lines, and no slots for the others).
  IntervalCache(const GridSpec& grid, const geom::LineSolid& solid, LineStore* store = nullptr,
                unsigned axes = 7u);
  ~IntervalCache();
  IntervalCache(const IntervalCache&) = delete;
  IntervalCache& operator=(const IntervalCache&) = delete;

  // Vertex box covering the solid's bounds, clipped to the stock (may be empty).
  const GridBox& touched() const { return touched_; }
  // Open intervals of the tool along the line of `axis` through vertex indices
  // (iu, iv) on axes (axis+1)%3 and (axis+2)%3; empty outside the bounds.
  // Throws std::logic_error for an axis the cache was not made for.
  std::span<const Span> line(int axis, int iu, int iv) const;
  // How many lineIntervals calls were made (for tests of "once per line").
  std::size_t queries() const { return queries_.load(std::memory_order_relaxed); }

 private:
  void fill(int axis, int iu, int iv, LineStore::Slot& slot) const;

  const GridSpec& grid_;
  const geom::LineSolid& solid_;
  GridBox touched_;
  std::unique_ptr<LineStore> owned_;
  LineStore* store_ = nullptr;
  std::uint32_t stamp_ = 0;
  unsigned axes_ = 7u;
  std::array<std::size_t, 3> base_{};  // first slot of each axis's lines
  mutable std::atomic<std::size_t> queries_{0};
};

}  // namespace mdhd::mdh

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

// A tool's chord along a line narrower than this (grid units) is dropped: a line that
// grazes a curved surface gets a width of rounding noise (interval_cache.cpp).
inline constexpr double kMinToolSpan = 1e-4;

class LineStore {
 public:
  LineStore();
  ~LineStore();
  LineStore(const LineStore&) = delete;
  LineStore& operator=(const LineStore&) = delete;

 private:
  friend class IntervalCache;
  // One line's intervals. Its state (kept apart, so the states of a step's
  // lines share cache lines) == the step's stamp: filled; stamp - 1: being
  // filled by another thread; anything else: not asked for yet this step.
  struct Slot {
    const Span* data = nullptr;
    std::uint32_t count = 0;
    Span inline_[2];  // a convex tool crosses a line once; a union of a few, twice
  };
  // Makes room for n slots and returns the stamp that marks this step's filled ones.
  std::uint32_t begin(std::size_t n);

  std::unique_ptr<std::atomic<std::uint32_t>[]> states_;
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

  const GridSpec& grid() const { return grid_; }
  // Vertex box covering the solid's bounds, clipped to the stock (may be empty).
  const GridBox& touched() const { return touched_; }
  // The solid's bounds along `axis` in grid units, unclipped: no line meets it
  // below lowest(axis) or above highest(axis).
  double lowest(int axis) const { return lowest_[axis]; }
  double highest(int axis) const { return highest_[axis]; }
  // Open intervals of the tool along the line of `axis` through vertex indices
  // (iu, iv) on axes (axis+1)%3 and (axis+2)%3; empty outside the bounds.
  // Throws std::logic_error for an axis the cache was not made for.
  // Always inlined: the hottest call of a cut (every column and crossing asks).
  [[gnu::always_inline]] std::span<const Span> line(int axis, int iu, int iv) const {
    if (static_cast<unsigned>(axis) > 2u || !(axes_ & (1u << axis))) wrongAxis();
    std::size_t i = 0;
    if (!slotOf(lines_[axis], iu, iv, i)) return {};
    if (store_->states_[i].load(std::memory_order_acquire) != stamp_) fillOnce(axis, iu, iv, i);
    const LineStore::Slot& slot = store_->slots_[i];
    return std::span<const Span>(slot.data, slot.count);
  }
  // Fills the lines along `axis` through (ius[i], iv), ius ascending, that no one
  // has filled this step, with one LineSolid::rowIntervals call (cheaper per line
  // than asking one by one); line() then finds them filled. Lines outside the
  // solid's box, and ones another thread is filling, are left to line().
  void fillRow(int axis, int iv, std::span<const int> ius) const;
  // Whether fillRow along `axis` is cheaper per line than line() (LineSolid::rowsPay).
  const geom::LineSolid& solid() const { return solid_; }
  bool rowsPay(int axis) const { return solid_.rowsPay(axis); }
  // The same lines' intervals as line() would give them, computed for the caller
  // alone (one LineSolid::rowIntervals call), with no slot claimed or filled: for lines
  // only one cell asks for, such as the z lines of a brick as tall as the stock. Line
  // i's are out[ends[i - 1] .. ends[i]) (from 0 for i = 0); outside the box, none.
  void rowSpans(int axis, int iv, std::span<const int> ius, std::vector<Span>& out,
                std::vector<std::size_t>& ends) const;
  // The same for any lines along `axis`, line i through (ius[i], ivs[i]), in any order
  // (one LineSolid::linesIntervals call): the x and y lines a cut will ask for at many
  // levels and rows.
  void fillLines(int axis, std::span<const int> ius, std::span<const int> ivs) const;
  // Whether fillLines along `axis` is cheaper per line than line() (LineSolid::linesPay).
  bool linesPay(int axis) const { return solid_.linesPay(axis); }
  // The solid's prism band (LineSolid::prismBand) as grid levels on `axis`: lines
  // square to it at levels in (lo, hi] are the line at lo. axis -1: none.
  struct PrismBand {
    int axis = -1, lo = 0, hi = -1;
    bool holds(int level) const { return level > lo && level <= hi; }
  };
  const PrismBand& prismBand() const { return band_; }
  // Whether several threads may ask for lines at once (the default). A cache
  // used by one thread skips the atomic claim of a line.
  void setShared(bool shared) { shared_ = shared; }
  // How many lineIntervals calls were made (for tests of "once per line"): the
  // lines filled this step, counted over the store (no shared counter to contend
  // for while cutting).
  std::size_t queries() const;

 private:
  // The lines of one axis in the store: (iu, iv) ranges and first slot.
  struct Lines {
    int ulo = 1, uhi = 0, vlo = 1, vhi = 0;  // empty unless the box is not
    std::size_t nu = 0, base = 0;
    int band = -1;  // band_'s levels are on this line's u (0) or v (1) coordinate, or none
  };
  [[noreturn]] static void wrongAxis();
  // The slot `i` of line (iu, iv), false outside the box. Inside the solid's prism
  // band one line answers for the whole stack: iu or iv become the band's first level.
  [[gnu::always_inline]] bool slotOf(const Lines& l, int& iu, int& iv, std::size_t& i) const {
    if (iu < l.ulo || iu > l.uhi || iv < l.vlo || iv > l.vhi) return false;
    if (l.band == 0 && band_.holds(iu)) iu = band_.lo;
    if (l.band == 1 && band_.holds(iv)) iv = band_.lo;
    i = l.base + static_cast<std::size_t>(iv - l.vlo) * l.nu + static_cast<std::size_t>(iu - l.ulo);
    return true;
  }
  // A slot claimed by a batch fill, with its state before the claim (restored if
  // the solid throws).
  struct Claimed {
    std::size_t slot;
    std::uint32_t was;
  };
  // The slot of line (iu, iv) (slotOf: iu, iv become the line that answers) if this
  // thread may fill it: claimed and appended to `claimed`. False outside the box and
  // where filled or being filled.
  bool claim(int axis, int& iu, int& iv, std::vector<Claimed>& claimed) const;
  // Asks `ask(out, ends)` for the claimed lines' intervals, stores them and marks the
  // slots filled.
  template <class Ask>
  void storeClaimed(int axis, const std::vector<Claimed>& claimed, Ask ask) const;
  void fillOnce(int axis, int iu, int iv, std::size_t i) const;
  void fill(int axis, int iu, int iv, LineStore::Slot& slot) const;
  // Stores one line's intervals (mm) in its slot as grid units, snapped and merged.
  void store(std::span<const geom::Interval> mm, int axis, LineStore::Slot& slot) const;

  const GridSpec& grid_;
  const geom::LineSolid& solid_;
  GridBox touched_;
  std::array<double, 3> lowest_{}, highest_{};
  std::unique_ptr<LineStore> owned_;
  LineStore* store_ = nullptr;
  std::uint32_t stamp_ = 0;
  unsigned axes_ = 7u;
  bool shared_ = true;
  std::array<Lines, 3> lines_{};  // first slot of each axis's lines
  PrismBand band_;
};

}  // namespace mdhd::mdh

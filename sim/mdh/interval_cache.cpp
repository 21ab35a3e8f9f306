#include "sim/mdh/interval_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <thread>

namespace mdhd::mdh {

LineStore::LineStore() = default;
LineStore::~LineStore() = default;

std::uint32_t LineStore::begin(std::size_t n) {
  if (n > capacity_) {
    capacity_ = std::max(n, capacity_ + capacity_ / 2);
    states_ = std::make_unique<std::atomic<std::uint32_t>[]>(capacity_);  // 0: none filled
    for (std::size_t i = 0; i < capacity_; ++i) states_[i].store(0, std::memory_order_relaxed);
    slots_ = std::make_unique<Slot[]>(capacity_);
  }
  stamp_ += 2;
  if (stamp_ == 0) {  // wrapped after 2^31 steps: forget every old stamp
    for (std::size_t i = 0; i < capacity_; ++i) states_[i].store(0);
    stamp_ = 2;
  }
  overflow_.clear();
  return stamp_;
}

namespace {

// Coordinates within 1e-9 of a grid plane are snapped onto it, so a tool face
// that sits on a grid level in millimetres does so in grid units too.
double snap(double g) {
  // std::round without the libm call (the hottest line of a fill); far from
  // the grid's range, where the cast could overflow, std::round itself.
  // Adding and taking away 1.5 * 2^52 rounds to the nearest integer (ties to
  // even, which differ from round() only at .5, where nothing snaps anyway).
  constexpr double kMagic = 6755399441055744.0;
  const double r = std::abs(g) < 1e15 ? (g + kMagic) - kMagic : std::round(g);
  return std::abs(g - r) < 1e-9 ? r : g;
}

// Sorts spans by their start and merges those that overlap or touch, in place;
// returns how many are left. The contract says sorted and disjoint already; the
// arithmetic relies on it, so make sure.
std::size_t sortAndMerge(Span* s, std::size_t n) {
  auto byLo = [](const Span& x, const Span& y) { return x.lo < y.lo; };
  if (!std::is_sorted(s, s + n, byLo)) std::sort(s, s + n, byLo);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (kept > 0 && s[k].lo <= s[kept - 1].hi)
      s[kept - 1].hi = std::max(s[kept - 1].hi, s[k].hi);
    else
      s[kept++] = s[k];
  }
  return kept;
}

// A line grazing a curved tool surface gets a chord of a width that is rounding
// noise: the square root of a discriminant that should be 0 (a ball's or a
// cylinder's tangent line: 1e-7 grid units and more). Kept, it would hold a vertex
// "strictly inside" on some lines and not on the next (vertex_rule.h), and a
// column of a side map would flicker from removed to kept along its length: a
// spurious overhang, and a split (thesis case A2's drills, radius 15 grid steps on
// grid lines, split 2-3 cells for it). Chords narrower than kMinToolSpan are not there.

// A line's intervals (mm) as grid units in `dst` (room for mm.size()): snapped, NaN,
// inverted and grazing ones dropped, sorted and merged; returns how many are left.
std::size_t cleanSpans(const GridSpec& grid, int axis, std::span<const geom::Interval> mm,
                       Span* dst) {
  if (mm.size() == 1) {  // the usual answer: nothing to sort or merge
    const Span s{snap(grid.toGrid(axis, mm[0].lo)), snap(grid.toGrid(axis, mm[0].hi))};
    dst[0] = s;
    return s.hi - s.lo > kMinToolSpan ? 1 : 0;  // false for NaN too
  }
  std::size_t n = 0;
  for (const geom::Interval& i : mm) {
    const Span s{snap(grid.toGrid(axis, i.lo)), snap(grid.toGrid(axis, i.hi))};
    if (s.hi - s.lo > kMinToolSpan) dst[n++] = s;
  }
  return sortAndMerge(dst, n);
}

}  // namespace

IntervalCache::IntervalCache(const GridSpec& grid, const geom::LineSolid& solid, LineStore* store,
                             unsigned axes)
    : grid_(grid), solid_(solid), store_(store), axes_(axes) {
  const geom::Aabb b = solid.bounds();
  for (int a = 0; a < 3; ++a) {
    const double lo = grid.toGrid(a, b.lo[a]);
    const double hi = grid.toGrid(a, b.hi[a]);
    lowest_[a] = lo;
    highest_[a] = hi;
    // Clamp in double first: a solid far outside must not overflow the cast.
    const double top = grid.cubes[a];
    const bool ok = std::isfinite(lo) && std::isfinite(hi) && lo <= hi;
    touched_.lo[a] = ok ? static_cast<int>(std::clamp(std::floor(lo), 0.0, top + 1.0)) : 1;
    touched_.hi[a] = ok ? static_cast<int>(std::clamp(std::ceil(hi), -1.0, top)) : 0;
  }
  if (touched_.empty()) return;
  std::size_t n = 0;
  for (int a = 0; a < 3; ++a) {
    if (!(axes_ & (1u << a))) continue;
    const int u = axisU(a), v = axisV(a);
    Lines& l = lines_[a];
    l = {touched_.lo[u],
         touched_.hi[u],
         touched_.lo[v],
         touched_.hi[v],
         static_cast<std::size_t>(touched_.points(u)),
         n};
    n += l.nu * static_cast<std::size_t>(touched_.points(v));
  }
  // Lines square to the band's axis at its grid levels meet the solid alike: they
  // share the slot of the band's first level.
  int bandAxis = -1;
  double bandLo = 0.0, bandHi = 0.0;
  if (solid.prismBand(bandAxis, bandLo, bandHi) && bandAxis >= 0 && bandAxis < 3) {
    const double glo = std::ceil(grid.toGrid(bandAxis, bandLo));
    const double ghi = std::floor(grid.toGrid(bandAxis, bandHi));
    // Clamped into the box, so the band's first level is a line of the box.
    const int klo = static_cast<int>(
        std::clamp(glo, static_cast<double>(touched_.lo[bandAxis]), grid.cubes[bandAxis] + 1.0));
    const int khi = static_cast<int>(std::clamp(ghi, -1.0, grid.cubes[bandAxis] + 1.0));
    if (std::isfinite(glo) && std::isfinite(ghi) && khi > klo) {
      band_ = {bandAxis, klo, khi};
      for (int a = 0; a < 3; ++a)
        if (a != bandAxis) lines_[a].band = axisU(a) == bandAxis ? 0 : 1;
    }
  }
  if (store_ == nullptr) {
    owned_ = std::make_unique<LineStore>();
    store_ = owned_.get();
  }
  stamp_ = store_->begin(n);
}

IntervalCache::~IntervalCache() = default;

void IntervalCache::store(std::span<const geom::Interval> mm, int axis,
                          LineStore::Slot& slot) const {
  if (mm.size() <= std::size(slot.inline_)) {
    // The usual answer (a convex tool: one interval, or none) is cleaned in the
    // slot itself, without the vector.
    slot.count = static_cast<std::uint32_t>(cleanSpans(grid_, axis, mm, slot.inline_));
    slot.data = slot.inline_;
    return;
  }
  thread_local std::vector<Span> spans;
  spans.resize(mm.size());
  const std::size_t kept = cleanSpans(grid_, axis, mm, spans.data());
  slot.count = static_cast<std::uint32_t>(kept);
  if (kept <= std::size(slot.inline_)) {
    std::copy_n(spans.begin(), kept, slot.inline_);
    slot.data = slot.inline_;
    return;
  }
  auto heap = std::make_unique<Span[]>(kept);
  std::copy_n(spans.begin(), kept, heap.get());
  slot.data = heap.get();
  const std::lock_guard lock(store_->overflowMutex_);
  store_->overflow_.push_back(std::move(heap));
}

void IntervalCache::fill(int axis, int iu, int iv, LineStore::Slot& slot) const {
  thread_local std::vector<geom::Interval> buf;
  buf.clear();
  const int u = axisU(axis), v = axisV(axis);
  solid_.lineIntervals(axis, grid_.toMm(u, iu), grid_.toMm(v, iv), buf);
  store(buf, axis, slot);
}

bool IntervalCache::claim(int axis, int& iu, int& iv, std::vector<Claimed>& claimed) const {
  std::size_t i = 0;
  if (!slotOf(lines_[axis], iu, iv, i)) return false;  // a band's repeats find it claimed
  std::atomic<std::uint32_t>& s = store_->states_[i];
  std::uint32_t state = s.load(std::memory_order_acquire);
  if (state == stamp_ || state == stamp_ - 1) return false;
  if (shared_) {
    if (!s.compare_exchange_strong(state, stamp_ - 1, std::memory_order_acquire)) return false;
  } else {
    s.store(stamp_ - 1, std::memory_order_relaxed);
  }
  claimed.push_back({i, state});
  return true;
}

template <class Ask>
void IntervalCache::storeClaimed(int axis, const std::vector<Claimed>& claimed, Ask ask) const {
  thread_local std::vector<geom::Interval> out;
  thread_local std::vector<std::size_t> ends;
  out.clear();
  ends.resize(claimed.size());
  try {
    ask(out, std::span<std::size_t>(ends));
    std::size_t from = 0;
    for (std::size_t j = 0; j < claimed.size(); ++j) {
      store(std::span<const geom::Interval>(out.data() + from, ends[j] - from), axis,
            store_->slots_[claimed[j].slot]);
      from = ends[j];
    }
  } catch (...) {
    for (const Claimed& c : claimed)
      store_->states_[c.slot].store(c.was, std::memory_order_release);  // anyone may retry
    throw;
  }
  for (const Claimed& c : claimed) store_->states_[c.slot].store(stamp_, std::memory_order_release);
}

void IntervalCache::fillRow(int axis, int iv, std::span<const int> ius) const {
  if (static_cast<unsigned>(axis) > 2u || !(axes_ & (1u << axis))) wrongAxis();
  const Lines& l = lines_[axis];
  if (iv < l.vlo || iv > l.vhi) return;
  if (l.band == 1 && band_.holds(iv)) iv = band_.lo;
  thread_local std::vector<Claimed> claimed;
  thread_local std::vector<double> us;
  claimed.clear();
  us.clear();
  for (int iu : ius) {
    // In the band, u moves to the band's first level: still ascending.
    int v = iv;  // mapped already
    if (claim(axis, iu, v, claimed)) us.push_back(grid_.toMm(axisU(axis), iu));
  }
  if (claimed.empty()) return;
  const double v = grid_.toMm(axisV(axis), iv);
  storeClaimed(axis, claimed, [&](std::vector<geom::Interval>& out, std::span<std::size_t> ends) {
    solid_.rowIntervals(axis, us, v, out, ends);
  });
}

void IntervalCache::rowSpans(int axis, int iv, std::span<const int> ius, std::vector<Span>& out,
                             std::vector<std::size_t>& ends) const {
  if (static_cast<unsigned>(axis) > 2u || !(axes_ & (1u << axis))) wrongAxis();
  out.clear();
  ends.assign(ius.size(), 0);
  const Lines& l = lines_[axis];
  thread_local std::vector<double> us;
  thread_local std::vector<std::size_t> at, mmEnds;
  thread_local std::vector<geom::Interval> mm;
  us.clear();
  at.clear();
  // A band maps lines to its first level: the answers are the ones line() gives there.
  int v = iv;
  if (l.band == 1 && band_.holds(v)) v = band_.lo;
  for (std::size_t j = 0; j < ius.size(); ++j) {
    int iu = ius[j], w = v;
    std::size_t slot = 0;
    if (!slotOf(l, iu, w, slot)) continue;
    us.push_back(grid_.toMm(axisU(axis), iu));
    at.push_back(j);
  }
  if (!us.empty()) {
    mm.clear();
    mmEnds.resize(us.size());
    solid_.rowIntervals(axis, us, grid_.toMm(axisV(axis), v), mm, mmEnds);
  }
  // Cleaned as store() cleans a slot, line by line, into `out` (sized once: cleaning
  // never adds spans).
  out.resize(at.empty() ? 0 : mm.size());
  std::size_t from = 0, k = 0, n = 0;
  for (std::size_t j = 0; j < ius.size(); ++j) {
    if (k < at.size() && at[k] == j) {
      const std::span<const geom::Interval> line(mm.data() + from, mmEnds[k] - from);
      n += cleanSpans(grid_, axis, line, out.data() + n);
      from = mmEnds[k++];
    }
    ends[j] = n;
  }
  out.resize(n);
}

void IntervalCache::fillLines(int axis, std::span<const int> ius, std::span<const int> ivs) const {
  if (static_cast<unsigned>(axis) > 2u || !(axes_ & (1u << axis))) wrongAxis();
  thread_local std::vector<Claimed> claimed;
  thread_local std::vector<double> us, vs;
  claimed.clear();
  us.clear();
  vs.clear();
  for (std::size_t j = 0; j < ius.size() && j < ivs.size(); ++j) {
    int iu = ius[j], iv = ivs[j];
    if (!claim(axis, iu, iv, claimed)) continue;
    us.push_back(grid_.toMm(axisU(axis), iu));
    vs.push_back(grid_.toMm(axisV(axis), iv));
  }
  if (claimed.empty()) return;
  storeClaimed(axis, claimed, [&](std::vector<geom::Interval>& out, std::span<std::size_t> ends) {
    solid_.linesIntervals(axis, us, vs, out, ends);
  });
}

std::size_t IntervalCache::queries() const {
  std::size_t n = 0;
  if (store_ == nullptr) return n;  // an empty box asks for nothing
  for (const Lines& l : lines_) {
    const std::size_t end =
        l.base + l.nu * static_cast<std::size_t>(std::max(0, l.vhi - l.vlo + 1));
    for (std::size_t i = l.base; i < end; ++i)
      n += store_->states_[i].load(std::memory_order_relaxed) == stamp_;
  }
  return n;
}

void IntervalCache::wrongAxis() {
  throw std::logic_error("mdh: interval cache asked for lines it was not made for");
}

void IntervalCache::fillOnce(int axis, int iu, int iv, std::size_t i) const {
  std::atomic<std::uint32_t>& s = store_->states_[i];
  if (!shared_) {
    fill(axis, iu, iv, store_->slots_[i]);
    s.store(stamp_, std::memory_order_relaxed);
    return;
  }
  for (std::uint32_t state; (state = s.load(std::memory_order_acquire)) != stamp_;) {
    if (state == stamp_ - 1) {
      // Another thread is filling it (lines are shared only along brick faces).
      std::this_thread::yield();
      continue;
    }
    if (!s.compare_exchange_strong(state, stamp_ - 1, std::memory_order_acquire)) continue;
    try {
      fill(axis, iu, iv, store_->slots_[i]);
    } catch (...) {
      s.store(state, std::memory_order_release);  // not filled: anyone may retry
      throw;
    }
    s.store(stamp_, std::memory_order_release);
  }
}

}  // namespace mdhd::mdh

#include "sim/mdh/good_bad_map.h"

#include <algorithm>

namespace mdhd::mdh {

namespace {

std::size_t lineStart(const SampleGrid& g, int axis, int cu, int cv) {
  std::array<int, 3> p{};
  p[axis] = g.box().lo[axis];
  p[axisU(axis)] = cu;
  p[axisV(axis)] = cv;
  return g.index(p);
}

// Whether a vertex has a neighbour in the cell of the other state along some
// axis: a surface crossing on one of its edges.
bool nextToSurface(const SampleGrid& g, std::size_t i) {
  const bool solid = g.solidAt(i);
  const int n0 = g.size(0), n1 = g.size(1);
  const int at[3] = {static_cast<int>(i % n0), static_cast<int>(i / n0 % n1),
                     static_cast<int>(i / n0 / n1)};
  for (int a = 0; a < 3; ++a) {
    const std::size_t st = g.stride(a);
    if (at[a] > 0 && g.solidAt(i - st) != solid) return true;
    if (at[a] + 1 < g.size(a) && g.solidAt(i + st) != solid) return true;
  }
  return false;
}

}  // namespace

void markUnresolved(SampleGrid& g, Direction dir, const ThreeMap* oldMap, bool twoSided) {
  const int a = dir.axis, u = axisU(a), v = axisV(a), n = g.size(a);
  const std::size_t st = g.stride(a);
  const GridBox& box = g.box();
  const bool flips = oldMap != nullptr && oldMap->hasFlips();
  std::vector<int> changes;
  for (int cv = box.lo[v]; cv <= box.hi[v]; ++cv) {
    for (int cu = box.lo[u]; cu <= box.hi[u]; ++cu) {
      Direction old = dir;
      if (flips && oldMap->flipped(cu - box.lo[u], cv - box.lo[v])) old.sign = -old.sign;
      if (g.columnValid(old, cu, cv)) continue;
      if (twoSided && g.columnValid(Direction{a, -old.sign}, cu, cv)) continue;
      const std::size_t i0 = lineStart(g, a, cu, cv);
      changes.clear();
      for (int k = 0; k + 1 < n; ++k)
        if (g.solidAt(i0 + k * st) != g.solidAt(i0 + (k + 1) * st)) changes.push_back(k);
      if (changes.empty()) continue;
      // The one crossing the old heightmap can still hold: for +a the topmost
      // if it is solid-below, for -a the lowest if it is solid-above.
      int first = 0, last = static_cast<int>(changes.size()) - 1;
      if (old.sign > 0 && g.solidAt(i0 + changes[last] * st)) --last;
      if (old.sign < 0 && g.solidAt(i0 + (changes[0] + 1) * st)) ++first;
      if (first > last) continue;
      // Only the vertices next to the surface: the solid or empty run between
      // the crossings is not surface, and rays through it alone must not
      // count as unresolved (their regions would swallow the conflicts).
      for (int k = changes[first]; k <= changes[last] + 1; ++k)
        if (nextToSurface(g, i0 + k * st)) g.state(i0 + k * st) |= SampleGrid::kUnresolved;
    }
  }
}

GoodBadMap buildGoodBadMap(const SampleGrid& g, int axis) {
  GoodBadMap m;
  m.axis = axis;
  m.p = axisU(axis);
  m.q = axisV(axis);
  const GridBox& box = g.box();
  m.p0 = box.lo[m.p];
  m.q0 = box.lo[m.q];
  m.np = box.points(m.p);
  m.nq = box.points(m.q);
  m.type.assign(static_cast<std::size_t>(m.np) * m.nq, Pixel::kUnsigned);
  m.unresolved.assign(m.type.size(), 0);
  const int n = g.size(axis);
  const std::size_t st = g.stride(axis);
  for (int iq = 0; iq < m.nq; ++iq) {
    for (int ip = 0; ip < m.np; ++ip) {
      const std::size_t i0 = lineStart(g, axis, m.p0 + ip, m.q0 + iq);
      int changes = 0;
      bool firstDown = false;  // first change solid -> empty (a +axis surface)
      bool unresolved = false;
      for (int k = 0; k + 1 < n; ++k) {
        const std::uint8_t s0 = g.state(i0 + k * st), s1 = g.state(i0 + (k + 1) * st);
        if ((s0 & SampleGrid::kSolid) == (s1 & SampleGrid::kSolid)) continue;
        if (changes == 0) firstDown = s0 & SampleGrid::kSolid;
        ++changes;
        // The ray meets the unresolved surface (thesis 3.2) where one of its
        // own crossings lies next to it.
        unresolved |= ((s0 | s1) & SampleGrid::kUnresolved) != 0;
      }
      Pixel t = Pixel::kUnsigned;
      if (changes >= 2)
        t = Pixel::kBad;
      else if (changes == 1)
        t = firstDown ? Pixel::kPositive : Pixel::kNegative;
      const std::size_t at = m.at(ip, iq);
      m.type[at] = t;
      m.unresolved[at] = unresolved;
      m.hasBad |= t == Pixel::kBad;
      m.hasPositive |= t == Pixel::kPositive;
      m.hasNegative |= t == Pixel::kNegative;
      m.positives += t == Pixel::kPositive;
      m.negatives += t == Pixel::kNegative;
      m.hasUnresolvedBad |= t == Pixel::kBad && unresolved;
    }
  }
  return m;
}

}  // namespace mdhd::mdh

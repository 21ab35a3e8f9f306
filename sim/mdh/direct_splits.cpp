#include "sim/mdh/direct_splits.h"

#include <algorithm>
#include <climits>

namespace mdhd::mdh {

namespace {

// ComputeOverlapInterval (figure 3.17): shrinks `so` by every live segment of
// `list` that overlaps it, consuming those segments. Returns whether the set
// touches the unresolved surface (is not a type-4 set).
bool computeOverlapInterval(std::vector<DspSegment>& list, DspSegment& so) {
  bool touchesUnresolved = so.unresolvedL || so.unresolvedR;
  for (DspSegment& s : list) {
    if (!s.alive) continue;
    const int lo = std::max(so.lo, s.lo), hi = std::min(so.hi, s.hi);
    if (lo > hi) continue;
    so.lo = lo;
    so.hi = hi;
    touchesUnresolved |= s.unresolvedL || s.unresolvedR;
    s.alive = false;
  }
  so.unresolvedL = so.unresolvedR = touchesUnresolved;
  return touchesUnresolved;
}

bool anyAlive(const std::vector<DspSegment>& list) {
  return std::any_of(list.begin(), list.end(), [](const DspSegment& s) { return s.alive; });
}

void computeSets(std::vector<DspSegment>& in, std::vector<DspSegment>& out) {
  while (anyAlive(in)) {
    DspSegment so{INT_MIN, INT_MAX, false, false, true};
    if (computeOverlapInterval(in, so)) out.push_back(so);
  }
}

void expandSets(std::vector<DspSegment>& in, std::vector<DspSegment>& sets) {
  for (DspSegment& so : sets) {
    if (!anyAlive(in)) break;
    computeOverlapInterval(in, so);
  }
}

void relaxSets(const DspSegment& u, std::vector<DspSegment>& sets) {
  for (DspSegment& so : sets) {
    if (so.lo > u.hi) so.lo = u.hi;
    if (so.hi < u.lo) so.hi = u.lo;
  }
}

}  // namespace

std::vector<DspSegment> computeOverlapIntervals(DspSegment unresolved, std::vector<DspSegment> left,
                                                std::vector<DspSegment> tool,
                                                std::vector<DspSegment> right) {
  std::vector<DspSegment> sets;
  computeSets(tool, sets);  // step 1
  expandSets(left, sets);   // step 2
  expandSets(right, sets);
  computeSets(left, sets);  // step 3
  computeSets(right, sets);
  relaxSets(unresolved, sets);  // step 4
  return sets;
}

void directSplits(const SampleGrid& g, const GoodBadMap& map, const GridBox& cell,
                  std::vector<SplitCandidate>& out) {
  if (!map.hasUnresolvedBad) return;
  const int a = map.axis, n = g.size(a), lo = g.box().lo[a];
  const std::size_t st = g.stride(a);
  std::vector<DspSegment> left, tool, right;
  DspSegment u{INT_MAX, INT_MIN};
  std::vector<int> changes;
  for (int iq = 0; iq < map.nq; ++iq) {
    for (int ip = 0; ip < map.np; ++ip) {
      if (!map.unresolved[map.at(ip, iq)]) continue;
      std::array<int, 3> p{};
      p[a] = lo;
      p[map.p] = map.p0 + ip;
      p[map.q] = map.q0 + iq;
      const std::size_t i0 = g.index(p);
      changes.clear();
      for (int k = 0; k + 1 < n; ++k)
        if (g.solidAt(i0 + k * st) != g.solidAt(i0 + (k + 1) * st)) changes.push_back(k);
      auto unresolvedAt = [&](int k) {
        return ((g.state(i0 + k * st) | g.state(i0 + (k + 1) * st)) & SampleGrid::kUnresolved) != 0;
      };
      for (int k : changes) {
        if (!unresolvedAt(k)) continue;
        u.lo = std::min(u.lo, lo + k);
        u.hi = std::max(u.hi, lo + k + 1);
      }
      const int m = static_cast<int>(changes.size());
      for (int i = 0; i + 1 < m; ++i) {
        // Span between crossings i and i+1: a tool span is empty space the
        // cut has just made.
        bool toolSpan = false;
        for (int k = changes[i] + 1; k <= changes[i + 1]; ++k) {
          const std::uint8_t s = g.state(i0 + k * st);
          toolSpan |= !(s & SampleGrid::kSolid) && (s & SampleGrid::kWasSolid);
        }
        if (!toolSpan) continue;
        auto segment = [&](int j) {
          return DspSegment{lo + changes[j] + 1, lo + changes[j + 1], unresolvedAt(changes[j]),
                            unresolvedAt(changes[j + 1]), true};
        };
        tool.push_back(segment(i));
        if (i >= 1) left.push_back(segment(i - 1));
        if (i + 2 < m) right.push_back(segment(i + 1));
      }
    }
  }
  if (tool.empty() || u.lo > u.hi) return;
  const auto sets = computeOverlapIntervals(u, std::move(left), std::move(tool), std::move(right));
  std::vector<SplitCandidate> series;
  for (const DspSegment& s : sets) {
    const int plo = std::max(s.lo, cell.lo[a] + 1), phi = std::min(s.hi, cell.hi[a] - 1);
    if (plo <= phi) series.push_back({a, plo, phi, SplitType::kDirect, false, false});
  }
  for (SplitCandidate& c : series) c.sole = series.size() == 1;
  out.insert(out.end(), series.begin(), series.end());
}

}  // namespace mdhd::mdh

#include "sim/mdh/crossing_splits.h"

#include <algorithm>

namespace mdhd::mdh {

void crossingSplits(const SampleGrid& g, const GoodBadMap& map, const GridBox& cell,
                    std::vector<SplitCandidate>& out) {
  const bool signConflict = !map.hasBad && map.hasPositive && map.hasNegative;
  if (!map.hasBad && !signConflict) return;
  const int a = map.axis, n = g.size(a), lo = g.box().lo[a];
  const std::size_t st = g.stride(a);
  // Edge k joins vertices k and k + 1 (relative to lo); plane j (relative)
  // has edge k below it when k < j and above it when k >= j.
  std::vector<long long> badDiff(static_cast<std::size_t>(n) + 1, 0);
  std::vector<long long> pos(static_cast<std::size_t>(n), 0), neg(pos);
  for (int iq = 0; iq < map.nq; ++iq)
    for (int ip = 0; ip < map.np; ++ip) {
      const Pixel t = map.type[map.at(ip, iq)];
      if (t == Pixel::kUnsigned || (map.hasBad && t != Pixel::kBad)) continue;
      std::array<int, 3> p{};
      p[a] = lo;
      p[map.p] = map.p0 + ip;
      p[map.q] = map.q0 + iq;
      const std::size_t i0 = g.index(p);
      int first = -1, last = -1;
      for (int k = 0; k + 1 < n; ++k)
        if (g.solidAt(i0 + k * st) != g.solidAt(i0 + (k + 1) * st)) {
          if (first < 0) first = k;
          last = k;
        }
      if (t == Pixel::kBad) {
        badDiff[first + 1] += 1;  // planes first+1 .. last separate the outer crossings
        badDiff[last + 1] -= 1;
      } else {
        (t == Pixel::kPositive ? pos : neg)[first] += 1;
      }
    }
  // score[j] for relative planes j = 1 .. n-2 (strictly inside the cell).
  std::vector<long long> score(static_cast<std::size_t>(n), 0);
  long long run = 0, posBelow = 0, negBelow = 0, posAll = 0, negAll = 0;
  for (int k = 0; k < n; ++k) posAll += pos[k], negAll += neg[k];
  for (int j = 0; j < n; ++j) {
    run += badDiff[j];
    if (j > 0) posBelow += pos[j - 1], negBelow += neg[j - 1];
    score[j] = signConflict ? posBelow * (negAll - negBelow) + negBelow * (posAll - posBelow) : run;
  }
  const int jLo = std::max(1, cell.lo[a] + 1 - lo), jHi = std::min(n - 2, cell.hi[a] - 1 - lo);
  long long best = 0;
  for (int j = jLo; j <= jHi; ++j) best = std::max(best, score[j]);
  if (best == 0) return;
  const SplitType type = signConflict ? SplitType::kSignConflict : SplitType::kDirect;
  for (int j = jLo; j <= jHi; ++j) {
    if (score[j] != best) continue;
    int e = j;
    while (e + 1 <= jHi && score[e + 1] == best) ++e;
    out.push_back({a, lo + j, lo + e, type, false, false});
    j = e;
  }
}

}  // namespace mdhd::mdh

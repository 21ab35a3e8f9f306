#include "sim/mdh/line_segments.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace mdhd::mdh {

void subtractOpen(std::span<const Span> segments, std::span<const Span> tool,
                  std::vector<Span>& out) {
  out.clear();
  std::size_t t0 = 0;
  for (const Span& s : segments) {
    double lo = s.lo;
    bool alive = true;
    while (t0 < tool.size() && tool[t0].hi <= s.lo) ++t0;
    for (std::size_t t = t0; t < tool.size(); ++t) {
      if (tool[t].lo >= s.hi) break;
      if (tool[t].hi <= lo) continue;
      if (tool[t].lo >= lo) out.push_back({lo, tool[t].lo});
      lo = tool[t].hi;
      if (lo > s.hi) {
        alive = false;
        break;
      }
    }
    if (alive) out.push_back({lo, s.hi});
  }
}

void segmentsFromSamples(int first, std::span<const std::uint8_t> solid,
                         std::span<const double> crossing, std::vector<Span>& out) {
  out.clear();
  const int n = static_cast<int>(solid.size());
  int i = 0;
  while (i < n) {
    if (!solid[i]) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < n && solid[j + 1]) ++j;
    // A missing crossing (never expected) falls back to the edge midpoint.
    double lo = first + i;
    if (i > 0) lo = std::isnan(crossing[i - 1]) ? first + i - 0.5 : crossing[i - 1];
    double hi = first + j;
    if (j < n - 1) hi = std::isnan(crossing[j]) ? first + j + 0.5 : crossing[j];
    out.push_back({lo, hi});
    i = j + 1;
  }
}

namespace {

// std::nextafter towards +inf / -inf of a grid level (an integer), without the
// libm call: for a positive finite double the neighbours are one bit pattern away.
double nextUp(int k) {
  if (k <= 0) return std::nextafter(double(k), 1e300);
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(double(k)) + 1);
}
double nextDown(int k) {
  if (k <= 0) return std::nextafter(double(k), -1e300);
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(double(k)) - 1);
}

}  // namespace

bool strictlyInside(std::span<const Span> tool, double x) {
  for (const Span& t : tool) {
    if (t.lo >= x) return false;
    if (x < t.hi) return true;
  }
  return false;
}

double edgeCrossingAfterCut(bool o0, bool o1, double oc, bool n0, bool n1, int k,
                            std::span<const Span> tool) {
  // The usual case, a crossing in the tool's box that no tool interval reaches
  // (behind the tool, beside it, or by less than kToolSlack): the answer below
  // without walking the intervals.
  if (o0 == n0 && o1 == n1 && o0 != o1 && (o0 ? k <= oc : oc <= k + 1)) {
    const double lo = o0 ? double(k) : oc, hi = o0 ? oc : double(k + 1);  // the solid part
    bool reached = false;
    for (const Span& t : tool)
      reached = reached || (t.lo < hi - kToolSlack && t.hi > lo + kToolSlack);
    if (!reached)
      return o0 ? std::clamp(oc, double(k), nextDown(k + 1))
                : std::clamp(oc, nextUp(k), double(k + 1));
  }
  // The crossing lies in [k, k+1) when k is solid, in (k, k+1] when k+1 is.
  const double lo = n0 ? double(k) : nextUp(k);
  const double hi = n0 ? nextDown(k + 1) : double(k + 1);
  const double none = n0 ? lo : hi;
  if (!o0 && !o1) return none;
  if (std::isnan(oc)) oc = k + 0.5;
  const Span before = o0 && o1 ? Span{double(k), double(k + 1)}
                      : o0     ? Span{double(k), oc}
                               : Span{oc, double(k + 1)};
  // subtractOpen(before, tool), piece by piece: the first piece that holds the
  // solid end is the answer.
  double at = -1.0;
  const auto settles = [&](double plo, double phi) {
    if (n0 && !n1 && plo <= k) return at = std::clamp(phi, lo, hi), true;
    if (!n0 && n1 && phi >= k + 1) return at = std::clamp(plo, lo, hi), true;
    return false;
  };
  double from = before.lo;
  std::size_t t = 0;
  while (t < tool.size() && tool[t].hi <= before.lo) ++t;
  for (; t < tool.size() && tool[t].lo < before.hi; ++t) {
    if (tool[t].hi <= from) continue;
    if (tool[t].lo >= from && settles(from, tool[t].lo)) return at;
    from = tool[t].hi;
    if (from > before.hi) return none;  // nothing left after this interval
  }
  return settles(from, before.hi) ? at : none;
}

}  // namespace mdhd::mdh

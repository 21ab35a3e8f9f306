#pragma once
// Every grid line's solid intervals of a stock, flattened: two stocks hold the same
// solid to the bit when these are equal.
#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/mdh/stock.h"

namespace mdhd::mdh::testing {

inline std::vector<double> allIntervals(const Stock& stock) {
  std::vector<double> out;
  std::vector<geom::Interval> line;
  const GridSpec& g = stock.grid();
  for (int axis = 0; axis < 3; ++axis) {
    const int u = axisU(axis), v = axisV(axis);
    for (int iv = 0; iv <= g.cubes[v]; ++iv)
      for (int iu = 0; iu <= g.cubes[u]; ++iu) {
        line.clear();
        stock.solidIntervals(axis, iu, iv, line);
        for (const geom::Interval& i : line) out.insert(out.end(), {i.lo, i.hi});
        out.push_back(-1.0);  // line separator
      }
  }
  return out;
}

// How many entries of two allIntervals() differ by more than `tolerance` mm (all of
// the longer one's tail).
inline int differences(const std::vector<double>& a, const std::vector<double>& b,
                       double tolerance = 0.0) {
  int apart = static_cast<int>(a.size() > b.size() ? a.size() - b.size() : b.size() - a.size());
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    apart += !(std::abs(a[k] - b[k]) <= tolerance);
  return apart;
}

}  // namespace mdhd::mdh::testing

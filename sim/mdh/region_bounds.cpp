#include "sim/mdh/region_bounds.h"

#include <algorithm>
#include <numeric>

namespace mdhd::mdh {

namespace {

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<PixelRect> regionBounds(const GoodBadMap& map,
                                    const std::function<bool(std::size_t)>& member) {
  // Row by row: runs of member pixels are labelled, and a run touching a run
  // of the previous row joins its region (union-find keeps merges exact).
  std::vector<int> label(map.type.size(), -1);
  std::vector<int> parent;
  std::vector<PixelRect> rect;
  for (int iq = 0; iq < map.nq; ++iq) {
    for (int ip = 0; ip < map.np; ++ip) {
      const std::size_t at = map.at(ip, iq);
      if (!member(at)) continue;
      int l = -1;
      if (ip > 0 && label[at - 1] >= 0) l = findRoot(parent, label[at - 1]);
      if (iq > 0 && label[at - map.np] >= 0) {
        const int up = findRoot(parent, label[at - map.np]);
        if (l < 0)
          l = up;
        else if (up != l)
          parent[up] = l;
      }
      if (l < 0) {
        l = static_cast<int>(parent.size());
        parent.push_back(l);
      }
      label[at] = l;
    }
  }
  std::vector<int> slot(parent.size(), -1);
  for (int iq = 0; iq < map.nq; ++iq) {
    for (int ip = 0; ip < map.np; ++ip) {
      const std::size_t at = map.at(ip, iq);
      if (label[at] < 0) continue;
      const int r = findRoot(parent, label[at]);
      const int p = map.p0 + ip, q = map.q0 + iq;
      if (slot[r] < 0) {
        slot[r] = static_cast<int>(rect.size());
        rect.push_back({p, p, q, q});
      }
      PixelRect& b = rect[slot[r]];
      b.p0 = std::min(b.p0, p);
      b.p1 = std::max(b.p1, p);
      b.q0 = std::min(b.q0, q);
      b.q1 = std::max(b.q1, q);
    }
  }
  return rect;
}

}  // namespace mdhd::mdh

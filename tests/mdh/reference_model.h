#pragma once
// The brute-force reference: the stock box minus a list of solids, asked
// point by point and by fine z-dexels for its volume.
#include <algorithm>
#include <memory>
#include <vector>

#include "sim/geometry/line_solid.h"

namespace mdhd::mdh::testing {

class ReferenceModel {
 public:
  explicit ReferenceModel(geom::Aabb box) : box_(box) {}
  void cut(std::shared_ptr<geom::LineSolid> s) { cuts_.push_back({s, s->bounds()}); }

  bool isSolid(const glm::dvec3& p) const {
    for (int a = 0; a < 3; ++a)
      if (p[a] < box_.lo[a] || p[a] > box_.hi[a]) return false;
    std::vector<geom::Interval> buf;
    for (const auto& c : cuts_) {
      if (p.x < c.b.lo.x || p.x > c.b.hi.x || p.y < c.b.lo.y || p.y > c.b.hi.y || p.z < c.b.lo.z ||
          p.z > c.b.hi.z)
        continue;
      buf.clear();
      c.s->lineIntervals(2, p.x, p.y, buf);
      for (const auto& i : buf)
        if (p.z > i.lo && p.z < i.hi) return false;
    }
    return true;
  }

  // Solid iff every point of a cube of half-size r around p agrees (26 probes)
  // and so do the lines of the cube along each axis through p and its edges' and
  // faces' midpoints (3 x 9, exactly, from the cuts' intervals): a sliver thinner
  // than r that the probes step over, such as a few hundredths a cut leaves on a
  // face of the box, still meets one of the lines. 0 empty, 1 solid, -1 near the
  // surface.
  int classify(const glm::dvec3& p, double r) const {
    const bool s = isSolid(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (isSolid(p + glm::dvec3(dx, dy, dz) * r) != s) return -1;
    for (int a = 0; a < 3; ++a)
      for (int du = -1; du <= 1; ++du)
        for (int dv = -1; dv <= 1; ++dv) {
          glm::dvec3 q = p;
          q[(a + 1) % 3] += du * r;
          q[(a + 2) % 3] += dv * r;
          if (!allAlong(a, q, r, s)) return -1;
        }
    return s ? 1 : 0;
  }

  // Volume by z-dexels on an n x n-per-mm midpoint grid.
  double volume(double perMm) const {
    const double step = 1.0 / perMm;
    double v = 0.0;
    std::vector<geom::Interval> segs, next, buf;
    for (double x = box_.lo.x + step / 2; x < box_.hi.x; x += step)
      for (double y = box_.lo.y + step / 2; y < box_.hi.y; y += step) {
        segs.assign(1, {box_.lo.z, box_.hi.z});
        for (const auto& c : cuts_) {
          if (x < c.b.lo.x || x > c.b.hi.x || y < c.b.lo.y || y > c.b.hi.y) continue;
          buf.clear();
          c.s->lineIntervals(2, x, y, buf);
          for (const auto& t : buf) {
            next.clear();
            for (const auto& s : segs) {
              if (t.hi <= s.lo || t.lo >= s.hi) {
                next.push_back(s);
                continue;
              }
              if (t.lo > s.lo) next.push_back({s.lo, t.lo});
              if (t.hi < s.hi) next.push_back({t.hi, s.hi});
            }
            segs.swap(next);
          }
        }
        for (const auto& s : segs) v += (s.hi - s.lo) * step * step;
      }
    return v;
  }

 private:
  // Whether the segment of the axis line through p within r of it is all solid
  // (`solid`) or all empty: the empty parts (outside the box, inside a cut) merged.
  bool allAlong(int a, const glm::dvec3& p, double r, bool solid) const {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const double s0 = p[a] - r, s1 = p[a] + r;
    if (p[u] < box_.lo[u] || p[u] > box_.hi[u] || p[v] < box_.lo[v] || p[v] > box_.hi[v])
      return !solid;  // outside the box
    std::vector<geom::Interval> empty{{-1e300, box_.lo[a]}, {box_.hi[a], 1e300}}, buf;
    for (const auto& c : cuts_) {
      if (p[u] < c.b.lo[u] || p[u] > c.b.hi[u] || p[v] < c.b.lo[v] || p[v] > c.b.hi[v]) continue;
      buf.clear();
      c.s->lineIntervals(a, p[u], p[v], buf);
      empty.insert(empty.end(), buf.begin(), buf.end());
    }
    std::sort(empty.begin(), empty.end(), [](auto& x, auto& y) { return x.lo < y.lo; });
    // The first merged empty run that meets (s0, s1) decides: all empty if it
    // covers it, both states if not. None meets it: all solid.
    double lo = empty.front().lo, hi = empty.front().hi;
    for (std::size_t i = 1; i <= empty.size(); ++i) {
      if (i < empty.size() && empty[i].lo <= hi) {
        hi = std::max(hi, empty[i].hi);
        continue;
      }
      if (lo < s1 && hi > s0) return !solid && lo <= s0 && hi >= s1;
      if (i < empty.size()) {
        lo = empty[i].lo;
        hi = empty[i].hi;
      }
    }
    return solid;
  }

  struct Cut {
    std::shared_ptr<geom::LineSolid> s;
    geom::Aabb b;
  };
  geom::Aabb box_;
  std::vector<Cut> cuts_;
};

}  // namespace mdhd::mdh::testing

#pragma once
// The hand-over from swept volumes to the stock: a solid that can say where an
// axis-parallel line runs inside it. The mdh-map samples every solid only
// through this, so tools, swept volumes and fixtures all plug in the same way.
#include <cstddef>
#include <span>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace mdhd::geom {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

struct Aabb {
  glm::dvec3 lo{0.0};
  glm::dvec3 hi{0.0};
};

class LineSolid {
 public:
  virtual ~LineSolid() = default;
  // A box that contains the whole solid.
  virtual Aabb bounds() const = 0;
  // A box that contains the part of the solid inside `box` (lo > hi on some axis when
  // there is none). This default clips bounds(); a solid whose box is much larger than
  // its parts (a leaning tool) may say more.
  virtual Aabb boundsIn(const Aabb& box) const {
    const Aabb b = bounds();
    return {glm::max(b.lo, box.lo), glm::min(b.hi, box.hi)};
  }
  // Appends to `out` the intervals of coordinate `axis` (0 x, 1 y, 2 z) where the line
  // {p : p[(axis+1)%3] = u, p[(axis+2)%3] = v} lies inside the solid: sorted, disjoint.
  virtual void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const = 0;
  // Many lines along `axis` with one v, at u = us[i] (ascending): appends line i's
  // intervals, exactly as lineIntervals gives them, to `out` and sets ends[i] to out's
  // size after them (ends.size() == us.size()). This default asks line by line; a
  // solid of many bodies may go body by body over the row, which is cheaper per line.
  virtual void rowIntervals(int axis, std::span<const double> us, double v,
                            std::vector<Interval>& out, std::span<std::size_t> ends) const {
    for (std::size_t i = 0; i < us.size(); ++i) {
      lineIntervals(axis, us[i], v, out);
      ends[i] = out.size();
    }
  }
  // Whether rowIntervals along `axis` is cheaper per line than lineIntervals (a stock
  // then asks for rows where it can; otherwise line by line, only what it needs).
  virtual bool rowsPay(int axis) const {
    (void)axis;
    return false;
  }
  // Many lines along `axis` at (us[i], vs[i]), in any order: appends line i's
  // intervals, exactly as lineIntervals gives them, to `out` and sets ends[i] to out's
  // size after them (ends.size() == us.size() == vs.size()). This default asks line
  // by line.
  virtual void linesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                              std::vector<Interval>& out, std::span<std::size_t> ends) const {
    for (std::size_t i = 0; i < us.size(); ++i) {
      lineIntervals(axis, us[i], vs[i], out);
      ends[i] = out.size();
    }
  }
  // Whether linesIntervals along `axis` is cheaper per line than lineIntervals.
  virtual bool linesPay(int axis) const {
    (void)axis;
    return false;
  }
  // A prism band: a grid axis `axis` and a range [lo, hi] of coordinates on it over
  // which every section square to it is the same (a tool on a grid axis translated,
  // along its cylinder). Lines square to `axis` that differ only in their coordinate
  // on it within [lo, hi] then meet the solid alike, so one answers for all (a wall
  // beside the tool is hundreds of such lines per step). False: no such band.
  virtual bool prismBand(int& axis, double& lo, double& hi) const {
    (void)axis, (void)lo, (void)hi;
    return false;
  }
};

}  // namespace mdhd::geom

#pragma once
// The sampling grid: vertices at integer multiples of h from the stock's min
// corner. Everything inside the engine works in grid units (mm / h measured
// from that corner), so vertices are exact integers and every stored height is
// an absolute coordinate along its line (thesis 7.4).
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace mdhd::mdh {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline int axisU(int axis) {
  return (axis + 1) % 3;
}
inline int axisV(int axis) {
  return (axis + 2) % 3;
}

// An inclusive box of grid vertices; a cell spans hi - lo cubes per axis.
struct GridBox {
  std::array<int, 3> lo{0, 0, 0};
  std::array<int, 3> hi{0, 0, 0};

  int points(int axis) const { return hi[axis] - lo[axis] + 1; }
  int cubes(int axis) const { return hi[axis] - lo[axis]; }
  bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
  std::int64_t pointCount() const { return std::int64_t{points(0)} * points(1) * points(2); }
  bool contains(const std::array<int, 3>& p) const {
    for (int a = 0; a < 3; ++a)
      if (p[a] < lo[a] || p[a] > hi[a]) return false;
    return true;
  }
  GridBox intersect(const GridBox& o) const {
    GridBox r;
    for (int a = 0; a < 3; ++a) {
      r.lo[a] = std::max(lo[a], o.lo[a]);
      r.hi[a] = std::min(hi[a], o.hi[a]);
    }
    return r;
  }
  bool operator==(const GridBox&) const = default;
};

// Where the grid sits in millimetres.
struct GridSpec {
  glm::dvec3 origin{0.0};
  double h = 0.1;
  std::array<int, 3> cubes{0, 0, 0};  // grid cubes per axis; vertices 0..cubes

  double toGrid(int axis, double mm) const { return (mm - origin[axis]) / h; }
  double toMm(int axis, double g) const { return origin[axis] + g * h; }
  GridBox all() const { return GridBox{{0, 0, 0}, cubes}; }
};

}  // namespace mdhd::mdh

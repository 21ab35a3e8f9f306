#pragma once
// Solids that do not move: fixtures and stock-like boxes, and cylinders at any angle.
#include <memory>

#include "sim/geometry/line_solid.h"
#include "sim/geometry/swept_volume.h"

namespace mdhd::geom {

// An axis-aligned box [lo, hi] (lo <= hi on every axis; throws std::invalid_argument
// otherwise or for non-finite corners).
class BoxSolid final : public LineSolid {
 public:
  BoxSolid(const glm::dvec3& lo, const glm::dvec3& hi);
  Aabb bounds() const override { return box_; }
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override;

 private:
  Aabb box_;
};

// The cylinder of `radius` from `base` along `axis` (any direction, normalised here)
// for `height`. Throws std::invalid_argument for a zero axis or a size that is not > 0.
class CylinderSolid final : public LineSolid {
 public:
  CylinderSolid(const glm::dvec3& base, const glm::dvec3& axis, double radius, double height);
  Aabb bounds() const override { return solid_.bounds(); }
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override {
    solid_.lineIntervals(axis, u, v, out);
  }
  void rowIntervals(int axis, std::span<const double> us, double v, std::vector<Interval>& out,
                    std::span<std::size_t> ends) const override {
    solid_.rowIntervals(axis, us, v, out, ends);
  }
  bool rowsPay(int axis) const override { return solid_.rowsPay(axis); }
  void linesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                      std::vector<Interval>& out, std::span<std::size_t> ends) const override {
    solid_.linesIntervals(axis, us, vs, out, ends);
  }
  bool linesPay(int axis) const override { return solid_.linesPay(axis); }

 private:
  SweptVolume solid_;  // a one-piece part standing at one pose
};

}  // namespace mdhd::geom

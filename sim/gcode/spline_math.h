#pragma once
// Planar NURBS curves as LinuxCNC defines G5 / G5.1 / G5.2 (its canon's
// NURBS_FEED): order k (degree k - 1), clamped uniform integer knots
// (k zeros, 1 .. n-k+1, k times n-k+2, for n+1 control points), rational
// with the weights of the control points. G5.1 is the order-3 curve of three
// points (a quadratic Bezier), G5 the order-4 curve of four (a cubic Bezier).
#include <array>
#include <vector>

namespace mdhd::gcode {

struct ControlPoint {
  double x = 0.0, y = 0.0;
  double w = 1.0;  // weight, > 0
};

using PlanePoint = std::array<double, 2>;

class NurbsCurve {
 public:
  // Needs order >= 2 and at least `order` points with positive weights.
  NurbsCurve(std::vector<ControlPoint> points, int order);

  double uMax() const { return u_max_; }  // the parameter runs over [0, uMax()]
  PlanePoint at(double u) const;

 private:
  std::vector<ControlPoint> points_;
  std::vector<double> knots_;
  int order_;
  double u_max_;
  mutable std::vector<std::array<double, 3>> work_;  // de Boor scratch (homogeneous)
};

// Appends to `out` a polyline that stays within `tolerance` (chordal
// deviation, same units as the points) of the curve: the points after the
// start, ending exactly at the last control point. Never more than
// `max_points` points (fewer when the tolerance allows).
void flattenCurve(const NurbsCurve& curve, const PlanePoint& last_control, double tolerance,
                  std::vector<PlanePoint>& out, std::size_t max_points = 1000000);

}  // namespace mdhd::gcode

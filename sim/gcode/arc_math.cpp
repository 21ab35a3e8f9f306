#include "sim/gcode/arc_math.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace mdhd::gcode {
namespace {
constexpr double kMmPerInch = 25.4;
constexpr double kTiny = 1e-12;
constexpr double kPi = std::numbers::pi;
}  // namespace

ArcTolerance arcTolerance(bool inch) {
  // LinuxCNC's CENTER_ARC_RADIUS_TOLERANCE_* and RADIUS_TOLERANCE_* constants.
  const double radius_inch = 0.00005;
  if (inch) {
    const double centre = 2 * 0.001 * std::numbers::sqrt2 * kMmPerInch;
    return {radius_inch * kMmPerInch, centre, 0.001, radius_inch * kMmPerInch};
  }
  const double centre = 2 * 0.01 * std::numbers::sqrt2;
  return {radius_inch * kMmPerInch, centre, 0.001, radius_inch * kMmPerInch};
}

std::string arcFromCenter(bool ccw, double s1, double s2, double e1, double e2, double i, double j,
                          bool absolute, int turns, const ArcTolerance& tol, double unit, char a,
                          char b, ArcFit& out) {
  out.center1 = absolute ? i : s1 + i;
  out.center2 = absolute ? j : s2 + j;
  const double r1 = std::hypot(out.center1 - s1, out.center2 - s2);
  const double r2 = std::hypot(out.center1 - e1, out.center2 - e2);
  char text[400];
  auto describe = [&](const char* what) {
    std::snprintf(text, sizeof text,
                  "%s: start=(%c%.4f,%c%.4f) center=(%c%.4f,%c%.4f) end=(%c%.4f,%c%.4f) "
                  "r1=%.4f r2=%.4f",
                  what, a, s1 / unit, b, s2 / unit, a, out.center1 / unit, b, out.center2 / unit, a,
                  e1 / unit, b, e2 / unit, r1 / unit, r2 / unit);
    return std::string(text);
  };
  if (r1 < tol.radius_min || r2 < tol.radius_min) return describe("Zero-radius arc");
  const double abs_err = std::fabs(r1 - r2);
  const double rel_err = abs_err / std::max(r1, r2);
  // LinuxCNC: an end off the radius by up to the tolerance is fine; beyond it, only
  // by up to 0.1 % of the radius, and never by 100 times the tolerance.
  if (abs_err > 100.0 * tol.spiral_abs || (rel_err > tol.spiral_rel && abs_err > tol.spiral_abs)) {
    std::string msg = describe("Radius to end of arc differs from radius to start");
    std::snprintf(text, sizeof text, " abs_err=%.4g rel_err=%.4f%%", abs_err / unit, rel_err * 100);
    return msg + text;
  }
  out.turn = ccw ? turns : -turns;
  return {};
}

std::string arcFromRadius(bool ccw, double s1, double s2, double e1, double e2, double radius,
                          int turns, const ArcTolerance& tol, ArcFit& out) {
  if (e1 == s1 && e2 == s2) return "Current point same as end point of arc";
  const double abs_radius = std::fabs(radius);
  const double mid1 = (e1 + s1) / 2.0;
  const double mid2 = (e2 + s2) / 2.0;
  double half = std::hypot(mid1 - e1, mid2 - e2);
  if (half - abs_radius > tol.r_format) return "Arc radius too small to reach end point";
  if (half / abs_radius > 1 - kTiny) half = abs_radius;  // a semicircle, up to rounding
  const double chord = std::atan2(e2 - s2, e1 - s1);
  const bool right = (!ccw && radius > 0) || (ccw && radius < 0);
  const double theta = right ? chord - kPi / 2 : chord + kPi / 2;
  const double offset = abs_radius * std::cos(std::asin(half / abs_radius));
  out.center1 = mid1 + offset * std::cos(theta);
  out.center2 = mid2 + offset * std::sin(theta);
  out.turn = ccw ? turns : -turns;
  return {};
}

double findTurn(double x1, double y1, double cx, double cy, int turn, double x2, double y2) {
  double alpha = std::atan2(y1 - cy, x1 - cx);
  double beta = std::atan2(y2 - cy, x2 - cx);
  if (turn > 0) {
    if (beta <= alpha) beta += 2 * kPi;
    return (beta - alpha) + (turn - 1) * (2 * kPi);
  }
  if (turn < 0) {
    if (alpha <= beta) alpha += 2 * kPi;
    return (beta - alpha) + (turn + 1) * (2 * kPi);
  }
  return 0.0;
}

double arcLength(double x1, double y1, double z1, double cx, double cy, int turn, double x2,
                 double y2, double z2) {
  const double radius = std::hypot(cx - x1, cy - y1);
  const double theta = findTurn(x1, y1, cx, cy, turn, x2, y2);
  if (z2 == z1) return radius * std::fabs(theta);
  return std::hypot(radius * theta, z2 - z1);
}

}  // namespace mdhd::gcode

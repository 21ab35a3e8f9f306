#pragma once
// Arc geometry as RS274/NGC (LinuxCNC 2.9) defines it, in a plane's first and
// second coordinates (G17: X,Y  G18: Z,X  G19: Y,Z). Lengths in mm.
#include <string>

namespace mdhd::gcode {

struct ArcFit {
  double center1 = 0.0, center2 = 0.0;
  int turn = 0;  // +n ccw, -n cw
};

// Tolerances of the radius checks, mm (they depend on the program's units).
struct ArcTolerance {
  double radius_min;  // smaller radius: a zero-radius arc
  double spiral_abs;  // |r_end - r_start| always allowed (100 times it never)
  double spiral_rel;  // beyond spiral_abs, allowed relative to the larger radius
  double r_format;    // R arcs: allowed shortfall of the radius
};
ArcTolerance arcTolerance(bool inch);

// Centre from I/J (absolute or relative to start). Returns an error message or "".
// unit: mm per program unit, for the numbers in the message. axis1/axis2: letters.
std::string arcFromCenter(bool ccw, double start1, double start2, double end1, double end2,
                          double i, double j, bool absolute, int turns, const ArcTolerance& tol,
                          double unit, char axis1, char axis2, ArcFit& out);

// Centre from radius R (negative: the long way). Returns an error message or "".
std::string arcFromRadius(bool ccw, double start1, double start2, double end1, double end2,
                          double radius, int turns, const ArcTolerance& tol, ArcFit& out);

// Signed swept angle (radians) from start to end about centre for turn.
double findTurn(double x1, double y1, double cx, double cy, int turn, double x2, double y2);

// Length of a helix: arc in the plane plus the axial travel.
double arcLength(double x1, double y1, double z1, double cx, double cy, int turn, double x2,
                 double y2, double z2);

}  // namespace mdhd::gcode

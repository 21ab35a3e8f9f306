#pragma once
// Lines parallel to the tool's axis through a translational sweep, in closed form.
//
// Every body a tool makes (cutter, shank, holder section) widens from its bottom face
// to a top face at its widest radius. Along a line parallel to the axis at distance
// rho from it, such a body holds [zLow(rho), top]: zLow is the lower envelope, 0 over
// the bottom face, then rising over the pieces that widen. Shifted back by s along the
// move, the line's distance is rho(s) = |q - s d| (q, d across the axis), so the sweep
// holds [min_s (zLow(rho(s)) + k s), top + max_s k s] (k: the move's component along
// the line), over the s in [0, L] with rho(s) <= the widest radius. The minimum is of
// a convex function of s; each rising piece's stationary point has a closed form, so
// one pass over the rising pieces finds it (no candidate enumeration, no allocation).
#include <cstddef>
#include <optional>
#include <vector>

#include "sim/geometry/tool_part.h"

namespace mdhd::geom {

// The lower envelope of a body whose radius never shrinks from bottom to top.
struct AxialProfile {
  // One rising piece: radius r0 at z0 to r1 at z1 (r0 < r1), a frustum (dz/drho =
  // slope) or a zone of a sphere below its centre.
  struct Rise {
    double r0 = 0, r1 = 0, r0sq = 0, r1sq = 0, z0 = 0, z1 = 0;
    bool sphere = false;
    double slope = 0;                 // frustum: dz / drho
    double k2 = 0;                    // frustum: (drho / dz)^2
    double centre = 0, radiusSq = 0;  // sphere
  };
  double bottom = 0, top = 0;
  double bottomRadiusSq = 0;  // the bottom face reaches this radius (squared)
  double maxRadius = 0, maxRadiusSq = 0;
  double riseTop = 0;  // where the radius first reaches maxRadius
  std::vector<Rise> rises;

  // zLow at the squared radius rho2 <= maxRadiusSq (clamped there).
  double lowAt(double rho2) const;
};

// The profile of `body`, or nothing when its radius shrinks somewhere, its pieces do
// not join, or a piece is neither a frustum nor a sphere zone below its centre (the
// general solver handles those).
std::optional<AxialProfile> axialProfile(const ConvexBody& body);

// The move seen from lines along one axis: d = the unit move's components across the
// axis (on (axis+1)%3, (axis+2)%3), a = |d|^2, k = the component along the line
// measured in the body's own height (the move's component times the axis' sign).
struct AxialMove {
  double d1 = 0, d2 = 0, a = 0, k = 0, length = 0;
};

// The extent [lo, hi] of body heights (relative to the tip, along the axis) that the
// swept body holds on the line at offset (q1, q2) from the tip; false if it misses.
// A line within `linearTol` (mm) outside the widest radius still runs along the wall.
bool axialExtent(const AxialProfile& profile, const AxialMove& move, double q1, double q2,
                 double linearTol, double& lo, double& hi);

// axialExtent for n lines of one row (offsets q1[i], q2), without a branch per line: what
// a line's answer takes is selected, not branched to, so a row runs at the arithmetic's
// pace. hit[i], lo[i], hi[i] are axialExtent's result and extent, to the bit (lo and hi
// are meaningless where hit[i] is 0). For profiles of up to kRowRises rises.
inline constexpr std::size_t kRowRises = 4;
void axialExtentRow(const AxialProfile& profile, const AxialMove& move, const double* q1, double q2,
                    std::size_t n, double linearTol, double* lo, double* hi, unsigned char* hit);

}  // namespace mdhd::geom

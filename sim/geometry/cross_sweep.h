#pragma once
// Lines square to the tool's axis through a translational sweep of one piece, in
// closed form: the line keeps one height on the axis, so shifted back by s along the
// move it meets the piece's disk at height zeta0 - s zd, of squared radius
// R^2(zeta0 - s zd), at distance h0 - s dn from the centre. Its chord there is
// s de +- sqrt(Q(s)), Q(s) = R^2(zeta0 - s zd) - (h0 - s dn)^2, a quadratic in s.
// The extremes over the s the piece's height range allows are at the two ends of that
// range or where the chord's end turns (one quadratic): no candidate enumeration.
#include <cstddef>

namespace mdhd::geom {

// A piece: x^2 + y^2 <= alpha + beta z + gamma z^2 for z0 <= z <= z1.
struct PieceQuadric {
  double z0 = 0, z1 = 0, alpha = 0, beta = 0, gamma = 0;
};

// The move seen from a line square to the axis: zd, dn, de = the unit move's
// components along the axis, across the line (in the plane square to the axis) and
// along the line; length = L; planar = hypot(dn, de), how fast the disks' centres move.
struct CrossMove {
  double zd = 0, dn = 0, de = 0, length = 0, planar = 0;
};

// The extent [lo, hi] along the line (relative to the tip's coordinate) of the
// piece's sweep on the line at height zeta0 on the axis and distance h0 across it;
// false if it misses. `linearTol` (mm) and `quadricTol` (mm^2) keep grazing ends.
bool crossExtent(const PieceQuadric& p, const CrossMove& m, double zeta0, double h0,
                 double linearTol, double quadricTol, double& lo, double& hi);

// crossExtent for n lines at heights zeta0[i] and distances h0[i], without a branch per
// line: hit[i], lo[i], hi[i] are crossExtent's result and extent, to the bit (lo and hi
// are meaningless where hit[i] is 0).
void crossExtentRow(const PieceQuadric& p, const CrossMove& m, const double* zeta0,
                    const double* h0, std::size_t n, double linearTol, double quadricTol,
                    double* lo, double* hi, unsigned char* hit);

}  // namespace mdhd::geom

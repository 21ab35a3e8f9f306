#pragma once
// Machined surface area facing downwards (outward normal z < -0.01), measured on
// the stock's grid lines in all three axes: each crossing of the surface with a
// line of axis a stands for h^2 * |n| / |n_a| of surface, with the normal from
// the neighbouring lines' crossings; a crossing counts only on the lines of its
// normal's dominant axis (the first of two tied), so steep walls are measured by the lines across
// them and never as stair steps. Only leaves that are not +z heightmaps can hold such surface, so
// only their region is sampled; the stock box's own faces are not machined surface and do not
// count.
#include "sim/mdh/stock.h"

namespace mdhd::check {

inline constexpr double kOverhangNormalZ = -0.01;

// `threads` (>= 1) read the grid lines; the area is the same for any count.
double overhangArea(const mdh::Stock& stock, int threads = 1);

}  // namespace mdhd::check

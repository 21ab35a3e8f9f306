#pragma once
// Ready-made machines, one per common 5-axis layout (docs/kinematics.md sketches
// each chain). Lengths in mm; every machine has X Y Z and a vertical spindle at
// zero, W = machine frame with all joints at zero.
#include "sim/kinematics/machine.h"

namespace mdhd::kin::presets {

// X Y Z in the tool chain, empty workpiece chain.
Machine threeAxisMill();
// Table-table: A cradle about X (its axis at the W origin), C table on top of it.
Machine acTrunnion();
// Table-table: B cradle about Y, its axis 50 mm below the W origin; C table on top.
Machine bcTrunnion();
// Head-table: B swivel head about Y, pivot 100 mm above the gauge point; C table.
Machine bcHeadTable();
// Head-head: A about X then B about Y (in A's frame), both pivots 100 mm above the
// gauge point.
Machine abHeadHead();
// Head-head fork: C turns the head about the vertical line through the gauge point,
// B tilts it about Y (in C's frame) with the pivot 100 mm above the gauge point.
Machine bcHeadHead();
// Nutating head (DMU style): B about an axis tilted 45 degrees in the YZ plane,
// (0, 1, 1)/sqrt 2 through a point 100 mm above the gauge point; B180 makes the
// spindle horizontal. C table.
Machine nutatingB45();

}  // namespace mdhd::kin::presets

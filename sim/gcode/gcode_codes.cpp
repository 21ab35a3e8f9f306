#include "sim/gcode/gcode_codes.h"

#include <array>

namespace mdhd::gcode {
namespace {

constexpr std::array kGCodes{
    CodeInfo{'G', 0, kGMotion, true, "rapid positioning"},
    CodeInfo{'G', 10, kGMotion, true, "linear feed"},
    CodeInfo{'G', 20, kGMotion, true, "clockwise arc"},
    CodeInfo{'G', 30, kGMotion, true, "counterclockwise arc"},
    CodeInfo{'G', 40, kGNonModal, false, "dwell"},
    CodeInfo{'G', 50, kGMotion, true, "cubic spline"},
    CodeInfo{'G', 51, kGMotion, true, "quadratic B-spline"},
    CodeInfo{'G', 52, kGMotion, true, "NURBS control point"},
    CodeInfo{'G', 53, kGNonModal, false, "end of NURBS"},
    CodeInfo{'G', 100, kGNonModal, true, "set offsets (L1, L2, L10, L11, L20)"},
    CodeInfo{'G', 170, kGPlane, false, "XY plane"},
    CodeInfo{'G', 180, kGPlane, false, "XZ plane"},
    CodeInfo{'G', 190, kGPlane, false, "YZ plane"},
    CodeInfo{'G', 200, kGUnits, false, "inch units"},
    CodeInfo{'G', 210, kGUnits, false, "millimetre units"},
    CodeInfo{'G', 280, kGNonModal, true, "go to stored position 1"},
    CodeInfo{'G', 281, kGNonModal, false, "store position 1"},
    CodeInfo{'G', 300, kGNonModal, true, "go to stored position 2"},
    CodeInfo{'G', 330, kGMotion, true, "spindle synchronised motion"},
    CodeInfo{'G', 331, kGMotion, true, "rigid tapping"},
    CodeInfo{'G', 382, kGMotion, true, "probe toward, error if no contact"},
    CodeInfo{'G', 383, kGMotion, true, "probe toward"},
    CodeInfo{'G', 384, kGMotion, true, "probe away, error if no loss of contact"},
    CodeInfo{'G', 385, kGMotion, true, "probe away"},
    CodeInfo{'G', 301, kGNonModal, false, "store position 2"},
    CodeInfo{'G', 400, kGCutterComp, false, "cutter compensation off"},
    CodeInfo{'G', 410, kGCutterComp, false, "cutter compensation left"},
    CodeInfo{'G', 411, kGCutterComp, false, "dynamic cutter compensation left"},
    CodeInfo{'G', 420, kGCutterComp, false, "cutter compensation right"},
    CodeInfo{'G', 421, kGCutterComp, false, "dynamic cutter compensation right"},
    CodeInfo{'G', 430, kGToolLength, false, "tool length offset"},
    CodeInfo{'G', 431, kGToolLength, true, "dynamic tool length offset"},
    CodeInfo{'G', 432, kGToolLength, false, "additional tool length offset"},
    CodeInfo{'G', 434, kGToolLength, false, "tool centre point control"},
    CodeInfo{'G', 490, kGToolLength, false, "cancel tool length offset"},
    CodeInfo{'G', 520, kGNonModal, true, "local coordinate system offset"},
    CodeInfo{'G', 530, kGNonModal, false, "machine coordinates"},
    CodeInfo{'G', 540, kGCoordSystem, false, "work offset 1"},
    CodeInfo{'G', 550, kGCoordSystem, false, "work offset 2"},
    CodeInfo{'G', 560, kGCoordSystem, false, "work offset 3"},
    CodeInfo{'G', 570, kGCoordSystem, false, "work offset 4"},
    CodeInfo{'G', 580, kGCoordSystem, false, "work offset 5"},
    CodeInfo{'G', 590, kGCoordSystem, false, "work offset 6"},
    CodeInfo{'G', 591, kGCoordSystem, false, "work offset 7"},
    CodeInfo{'G', 592, kGCoordSystem, false, "work offset 8"},
    CodeInfo{'G', 593, kGCoordSystem, false, "work offset 9"},
    CodeInfo{'G', 610, kGPathMode, false, "exact path"},
    CodeInfo{'G', 611, kGPathMode, false, "exact stop"},
    CodeInfo{'G', 640, kGPathMode, false, "blending"},
    CodeInfo{'G', 730, kGMotion, true, "chip-break drilling cycle"},
    CodeInfo{'G', 740, kGMotion, true, "left-hand tapping cycle"},
    CodeInfo{'G', 800, kGMotion, false, "cancel canned cycle"},
    CodeInfo{'G', 810, kGMotion, true, "drilling cycle"},
    CodeInfo{'G', 820, kGMotion, true, "drilling cycle with dwell"},
    CodeInfo{'G', 830, kGMotion, true, "peck drilling cycle"},
    CodeInfo{'G', 840, kGMotion, true, "tapping cycle"},
    CodeInfo{'G', 850, kGMotion, true, "boring cycle, feed out"},
    CodeInfo{'G', 860, kGMotion, true, "boring cycle, spindle stop, rapid out"},
    CodeInfo{'G', 870, kGMotion, true, "back boring cycle"},
    CodeInfo{'G', 880, kGMotion, true, "boring cycle, spindle stop, manual out"},
    CodeInfo{'G', 890, kGMotion, true, "boring cycle, dwell, feed out"},
    CodeInfo{'G', 900, kGDistance, false, "absolute distance"},
    CodeInfo{'G', 901, kGArcDistance, false, "absolute arc centre"},
    CodeInfo{'G', 910, kGDistance, false, "incremental distance"},
    CodeInfo{'G', 911, kGArcDistance, false, "incremental arc centre"},
    CodeInfo{'G', 920, kGNonModal, true, "coordinate system offset"},
    CodeInfo{'G', 921, kGNonModal, false, "reset offsets and parameters"},
    CodeInfo{'G', 922, kGNonModal, false, "reset offsets, keep parameters"},
    CodeInfo{'G', 923, kGNonModal, false, "restore offsets from parameters"},
    CodeInfo{'G', 930, kGFeedMode, false, "inverse time feed"},
    CodeInfo{'G', 940, kGFeedMode, false, "units per minute feed"},
    CodeInfo{'G', 950, kGFeedMode, false, "units per revolution feed"},
    CodeInfo{'G', 960, kGSpindleMode, false, "constant surface speed"},
    CodeInfo{'G', 970, kGSpindleMode, false, "constant spindle speed"},
    CodeInfo{'G', 980, kGRetract, false, "retract to initial level"},
    CodeInfo{'G', 990, kGRetract, false, "retract to R level"},
};

constexpr std::array kMCodes{
    CodeInfo{'M', 0, kMStop, false, "program stop"},
    CodeInfo{'M', 10, kMStop, false, "optional program stop"},
    CodeInfo{'M', 20, kMStop, false, "program end"},
    CodeInfo{'M', 30, kMSpindle, false, "spindle clockwise"},
    CodeInfo{'M', 40, kMSpindle, false, "spindle counterclockwise"},
    CodeInfo{'M', 50, kMSpindle, false, "spindle stop"},
    CodeInfo{'M', 60, kMToolChange, false, "tool change"},
    CodeInfo{'M', 70, kMCoolant, false, "mist on"},
    CodeInfo{'M', 80, kMCoolant, false, "flood on"},
    CodeInfo{'M', 90, kMCoolant, false, "coolant off"},
    CodeInfo{'M', 190, kMSpindle, false, "orient spindle (stops it)"},
    CodeInfo{'M', 300, kMStop, false, "program end and rewind"},
    CodeInfo{'M', 480, kMOverride, false, "enable overrides"},
    CodeInfo{'M', 490, kMOverride, false, "disable overrides"},
    CodeInfo{'M', 500, kMOverride, false, "feed override control"},
    CodeInfo{'M', 510, kMOverride, false, "spindle override control"},
    CodeInfo{'M', 520, kMOverride, false, "adaptive feed control"},
    CodeInfo{'M', 530, kMOverride, false, "feed stop control"},
    CodeInfo{'M', 600, kMStop, false, "pallet change pause"},
    CodeInfo{'M', 610, kMToolChange, false, "set current tool"},
    // Digital and analog outputs, waiting on an input: no motion (a verifier has no I/O).
    CodeInfo{'M', 620, kMIo, false, "digital output on, synchronised with motion"},
    CodeInfo{'M', 630, kMIo, false, "digital output off, synchronised with motion"},
    CodeInfo{'M', 640, kMIo, false, "digital output on, immediately"},
    CodeInfo{'M', 650, kMIo, false, "digital output off, immediately"},
    CodeInfo{'M', 660, kMIo, false, "wait on input"},
    CodeInfo{'M', 670, kMIo, false, "analog output, synchronised with motion"},
    CodeInfo{'M', 680, kMIo, false, "analog output, immediately"},
};

template <std::size_t N>
const CodeInfo* find(const std::array<CodeInfo, N>& table, int code10) {
  for (const CodeInfo& c : table)
    if (c.code10 == code10) return &c;
  return nullptr;
}

}  // namespace

const CodeInfo* findGCode(int code10) {
  return find(kGCodes, code10);
}
const CodeInfo* findMCode(int code10) {
  return find(kMCodes, code10);
}

}  // namespace mdhd::gcode

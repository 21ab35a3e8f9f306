#pragma once
// The one table of G and M codes this interpreter knows: code x10 as an
// integer (G59.1 -> 591, no float compares), modal group, description.
// Modal groups follow LinuxCNC's numbering so messages and #<_...> agree.
#include <string_view>

namespace mdhd::gcode {

// G code modal groups (index into BlockWords::g).
enum GGroup : int {
  kGNonModal = 0,      // G4 G5.3 G10 G28 G28.1 G30 G30.1 G52 G53 G92 G92.1 G92.2 G92.3
  kGMotion = 1,        // G0 G1 G2 G3 G5 G5.1 G5.2 G33 G33.1 G38.x G73 G74 G80 G81..G89
  kGPlane = 2,         // G17 G18 G19
  kGDistance = 3,      // G90 G91
  kGArcDistance = 4,   // G90.1 G91.1
  kGFeedMode = 5,      // G93 G94 G95
  kGUnits = 6,         // G20 G21
  kGCutterComp = 7,    // G40 G41 G42 G41.1 G42.1
  kGToolLength = 8,    // G43 G43.1 G43.2 G43.4 G49
  kGRetract = 10,      // G98 G99
  kGCoordSystem = 12,  // G54 .. G59.3
  kGPathMode = 13,     // G61 G61.1 G64
  kGSpindleMode = 14,  // G96 G97
  kGGroupCount = 15,
};

// M code modal groups (index into BlockWords::m).
enum MGroup : int {
  kMStop = 0,    // M0 M1 M2 M30 M60
  kMToolChange,  // M6 M61
  kMSpindle,     // M3 M4 M5 M19
  kMCoolant,     // M7 M8 M9 (M7 and M8 may share a line)
  kMOverride,    // M48 .. M53
  kMIo,          // M62 .. M68 (digital and analog outputs, wait on input)
  kMGroupCount,
};

struct CodeInfo {
  char letter;     // 'G' or 'M'
  int code10;      // code x10
  int group;       // GGroup or MGroup
  bool uses_axes;  // takes X Y Z ... as its arguments
  std::string_view description;
};

// nullptr: not a code this interpreter knows.
const CodeInfo* findGCode(int code10);
const CodeInfo* findMCode(int code10);

}  // namespace mdhd::gcode

#pragma once
// The benchmark programs: the FreeCAD peer's dome (peers/freecad/gen_gcode.py dome,
// same formula and moves) and a 5-axis variant of it for an AC trunnion.
#include <string>

#include "sim/kinematics/kinematics.h"

namespace mdhd::bench {

// Dome part: z = max(kFloor, kCentreZ + sqrt(kSphere^2 - d^2)), d from (cx, cy).
inline constexpr double kSphere = 80.0;
inline constexpr double kApex = 28.0;
inline constexpr double kCentreZ = kApex - kSphere;
inline constexpr double kFloor = 10.0;
inline constexpr double kBall = 3.0;  // 6 mm ball end mill
inline constexpr double kSafe = 35.0;

double domeZ(double x, double y, double cx, double cy);

struct DomeProgram {
  std::string text;
  long moves = 0;
};

// gen_gcode.py's dome (lines x pts zigzag on X0..100 Y0..100) after a tool set-up
// (T1 M6, G43 H1, M3) that does not move. `setup` false: exactly the peer's file.
// passes >= 0: only that many passes of the zigzag, from pass `first` on (a slice for
// profiling; the tool plunges at the slice's start into the uncut stock).
DomeProgram domeProgram(int lines, int pts, bool setup, int passes = -1, int first = 0);

// The same zigzag over a dome centred at the W origin (stock -50..50), on an AC
// trunnion under G43.4: the table tilted A-15 while C swings from -30 to 30 degrees
// along each pass, the ball centre on the dome's offset surface (so the envelope is
// the design surface), the programmed tip = centre - r * axis in W.
DomeProgram tiltedDomeProgram(const kin::Kinematics& kin, double tool_length, int lines, int pts,
                              int passes = -1, int first = 0);

}  // namespace mdhd::bench

#pragma once
// The eleven examples of thesis section 6.1 as real tool motions: each motion
// is the swept volume of the tool's flutes between two poses. The thesis shows
// pictures only (and this copy of it has lost them), so shapes and sizes are
// our reading of the captions and of table 6.8 (D1's surface: stock 4 x 4 x 1 mm,
// ball radius 0.15 mm, 25 degrees, torus radius 1.69 mm); `guess` says what was
// guessed per case.
#include <string>
#include <vector>

#include "sim/geometry/line_solid.h"
#include "sim/geometry/tool.h"
#include "sim/geometry/tool_pose.h"

namespace mdhd::mdh::bench {

// One straight move of the tool tip with the axis slerped from a to b.
struct Motion {
  geom::ToolPose a;
  geom::ToolPose b;
};

struct ThesisCase {
  std::string name;
  geom::Aabb stock;
  geom::Tool tool;
  std::vector<Motion> motions;
  std::string guess;
};

// donutDegrees: the turn of one motion of the D and DS cases (the figures that
// would fix it are lost; 5 degrees unless a calibration says otherwise).
std::vector<ThesisCase> thesisCases(double donutDegrees = 5);

}  // namespace mdhd::mdh::bench

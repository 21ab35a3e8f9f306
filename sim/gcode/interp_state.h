#pragma once
// Everything a block may change: modal state, offsets, current position.
// Blocks are transactions: the executor works on a copy and commits it only
// when the whole block succeeded.
#include <array>

#include "sim/gcode/motion.h"

namespace mdhd::gcode {

inline constexpr double kMmPerInch = 25.4;
inline constexpr int kCoordSystems = 9;  // G54 .. G59.3

enum class CompSide { kOff, kLeft, kRight };

struct CycleMemory {  // what canned cycles remember between blocks
  bool initial_level_set = false;
  double initial_level = 0.0;  // Z (third axis) where the series started
  double bottom = 0.0;         // last Z (third-axis) word, mm
  double r = 0.0;
  double p = -1.0, q = -1.0;  // dwell, peck (-1: never given)
  double i = 0.0, j = 0.0, k = 0.0;
};

struct InterpState {
  // Modal groups (G codes as code x10).
  int motion = 800;  // LinuxCNC starts in G80
  Plane plane = Plane::kXY;
  bool inch = false;
  bool incremental = false;
  bool arc_absolute = false;  // G90.1
  FeedMode feed_mode = FeedMode::kUnitsPerMinute;
  CompSide comp_side = CompSide::kOff;
  double comp_radius = 0.0;  // mm
  bool comp_first_move = true;
  int tool_length_mode = 490;  // 430, 431, 434 or 490
  int coord_system = 0;        // 0..8: G54 .. G59.3
  int path_mode = 640;
  bool retract_to_r = true;  // G99; LinuxCNC starts in R_PLANE (its setup constructor)
  // Values.
  double feed = 0.0;       // mm/min (G94) or mm/rev (G95)
  double feed_word = 0.0;  // F as written (program units), for pure rotary moves
  double speed = 0.0;
  SpindleState spindle = SpindleState::kOff;
  bool mist = false, flood = false;
  // M48..M53 switches (#<_feed_override> ...): nothing a verifier models, but read back.
  bool feed_override = true, speed_override = true, adaptive_feed = false, feed_hold = true;
  int tool = 0;            // in the spindle
  int selected_tool = -1;  // T word seen (-1: none)
  // Positions in program coordinates (mm, degrees): under cutter compensation
  // `current` is the tool centre and `programmed` the programmed point.
  AxisValues current{};
  AxisValues programmed{};
  AxisValues g92{};  // G92 offsets
  bool g92_applied = false;
  AxisValues g92_saved{};  // #5211.. (G92.2 keeps them, G92.3 restores them)
  std::array<AxisValues, kCoordSystems> g5x{};
  std::array<double, kCoordSystems> rotation{};  // G10 L2 R, degrees
  double tool_length = 0.0;                      // Z offset in effect (G43/G43.1), mm
  int tool_length_tool = 0;                      // H of G43 / G43.4
  AxisValues g28{}, g30{};                       // stored machine positions
  // Last G38.x: where it stopped (program frame, mm) and whether it tripped;
  // probe_count tells a new result from an old one (#5061..#5070).
  AxisValues probe_point{};
  bool probe_tripped = false;
  int probe_count = 0;
  CycleMemory cycle;
  int nurbs_order = 3;  // G5.2 L (the points are BlockExecutor's, not copied per block)
  bool ended = false;   // M2/M30 seen
};

}  // namespace mdhd::gcode

#pragma once
// What the interpreter hands on: canonical motions and events, in machine axis
// values (mm, degrees), one way downstream to trace, the simulator, the daemon
// and the tests, each of which implements MotionSink.
#include <array>
#include <string>

#include "sim/gcode/error.h"

namespace mdhd::gcode {

// Canonical axis order. U V W exist only on machines that name them.
enum Axis : int { kX = 0, kY, kZ, kA, kB, kC, kU, kV, kW };
inline constexpr int kAxisCount = 9;
inline constexpr char kAxisLetters[kAxisCount + 1] = "XYZABCUVW";
using AxisValues = std::array<double, kAxisCount>;

enum class MotionType { kRapid, kFeed, kArc };
enum class Plane { kXY, kXZ, kYZ };                                          // G17 G18 G19
enum class FeedMode { kUnitsPerMinute, kInverseTime, kUnitsPerRevolution };  // G94 G93 G95
enum class SpindleState { kOff, kClockwise, kCounterClockwise };

struct Motion {
  MotionType type = MotionType::kRapid;
  SourcePos pos;  // the block that produced it (under G41/G42: as LinuxCNC, the
                  // block being read when the queued move is released)
  const std::string* block_text = nullptr;  // that block's text; valid during the callback
  AxisValues start{};                       // axis values where the motion starts
  AxisValues end{};                         // ... and ends. Linear: mm, rotary: degrees.
  // "Machine" values as LinuxCNC's canon commands them: program value + G92, rotated by
  // G10 L2 R, + G5x offset, + tool length offset (on Z while G43 is in effect).
  // When tcp is true (G43.4) X Y Z are instead the tool tip in W (program + G92 + G5x,
  // no tool length) and the linear joints are for the kinematics to solve.
  bool tcp = false;
  // Arcs (type kArc): centre in the same frame as start/end, for the plane's two axes
  // (G17: X,Y  G18: Z,X  G19: Y,Z, as canon's first/second), and turns: +n ccw, -n cw
  // about the plane normal, |turn| = 1 + full extra turns (P word).
  Plane plane = Plane::kXY;
  std::array<double, 2> center{};
  int turn = 0;
  // Feed as commanded for this move: mm/min under G94, mm/rev under G95; under G93 the
  // interpreter converts F into the rate of this move (mm/min), as LinuxCNC does.
  double feed = 0.0;
  FeedMode feed_mode = FeedMode::kUnitsPerMinute;
  double inverse_time = 0.0;  // the F word under G93 (1/min), else 0
  // G33 / G33.1: the move is locked to the spindle; feed_mode is kUnitsPerRevolution and
  // feed the pitch (mm per revolution, the K word).
  bool spindle_sync = false;
  double spindle_rpm = 0.0;
  SpindleState spindle = SpindleState::kOff;
  int tool = 0;       // tool number in the spindle (0: none)
  bool comp = false;  // produced under cutter radius compensation
};

enum class EventType {
  kDwell,        // value: seconds
  kToolChange,   // tool: new tool in the spindle
  kSpindle,      // spindle state / rpm changed
  kCoolant,      // value: 0 off, 1 mist, 2 flood
  kProgramStop,  // M0 / M1
  kProgramEnd,   // M2 / M30 / end of file
  kMessage,      // text: (MSG,...) (DEBUG,...)
};

struct Event {
  EventType type = EventType::kDwell;
  SourcePos pos;
  double value = 0.0;
  int tool = 0;
  SpindleState spindle = SpindleState::kOff;
  double spindle_rpm = 0.0;
  std::string text;
};

class MotionSink {
 public:
  virtual ~MotionSink() = default;
  virtual void motion(const Motion& m) = 0;
  virtual void event(const Event& /*e*/) {}
};

}  // namespace mdhd::gcode

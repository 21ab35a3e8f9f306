#pragma once
// Turns program-frame moves into the Motion records a MotionSink receives:
// machine values (G92, G10 L2 R rotation, G5x, tool length), start = the end of
// the previous motion, the feed as LinuxCNC's canon would command it.
#include "sim/gcode/block.h"
#include "sim/gcode/interp_state.h"
#include "sim/gcode/motion.h"

namespace mdhd::gcode {

// The feed a move carries, fixed when the move is commanded.
struct FeedInfo {
  double rate = 0.0;  // mm/min (mm/rev under G95)
  double raw = 0.0;   // the rate in program units as canon sees it (pure rotary: deg/min)
  FeedMode mode = FeedMode::kUnitsPerMinute;
  double inverse_time = 0.0;
  bool sync = false;  // G33/G33.1: rate is the pitch, mm/rev
};

// Program point -> machine values under the offsets of `s`.
AxisValues toMachine(const InterpState& s, const AxisValues& program);
// Machine values -> program point (inverse of toMachine).
AxisValues toProgram(const InterpState& s, const AxisValues& machine);

class MotionOutput {
 public:
  MotionOutput(MotionSink& sink, const AxisValues& start) : sink_(sink), machine_(start) {}

  void straight(MotionType type, const AxisValues& program_end, const InterpState& s,
                const Block& block, const FeedInfo& feed, bool comp);
  // Arc in plane s.plane; c1/c2 are the centre in the plane's first/second axis (program).
  void arc(const AxisValues& program_end, double c1, double c2, int turn, const InterpState& s,
           const Block& block, const FeedInfo& feed, bool comp);
  void event(const Event& e) { sink_.event(e); }
  const AxisValues& machine() const { return machine_; }
  // The same place in new terms (G43.4 on or off): the next motion starts here.
  void reexpress(const AxisValues& machine) { machine_ = machine; }

 private:
  void fill(MotionType type, const AxisValues& end, const InterpState& s, const Block& block,
            const FeedInfo& feed, bool comp);

  MotionSink& sink_;
  AxisValues machine_;
  Motion motion_;  // reused: no allocation per move
};

// Plane axes as canon orders them: G17 (X,Y,Z) G18 (Z,X,Y) G19 (Y,Z,X).
struct PlaneAxes {
  int first, second, normal;
};
PlaneAxes planeAxes(Plane p);

}  // namespace mdhd::gcode

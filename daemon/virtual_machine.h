#pragma once
// The simulated controller's machine: a MotionSink that PLAYS each interpreted
// motion in real time (scaled by `speed`), sampling its JointPath at the elapsed
// time (kin::motionSeconds sets each motion's duration) and publishing the joint
// values, tool, spindle state and current line as it goes. A feed hold freezes
// the program clock until released; a stop request ends the run.
#include <chrono>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <stdexcept>

#include "protocol/job.h"
#include "sim/gcode/motion.h"
#include "sim/kinematics/kinematics.h"

namespace mdhd::daemon {

// What the controller shows at one instant.
struct ControllerState {
  gcode::AxisValues joints{};
  int tool = 0;
  bool spindle_on = false;
  std::int64_t line = 0;
};

// Thrown out of motion()/event() when a stop is requested, to unwind the interpreter.
class PlaybackStopped : public std::runtime_error {
 public:
  PlaybackStopped() : std::runtime_error("playback stopped") {}
};

struct PlaybackHooks {
  std::function<void(const ControllerState&)> publish;  // called from the playing thread
  std::function<bool()> feed_hold;                      // true: hold (may be empty)
  std::function<bool()> stop_requested;                 // true: stop (may be empty)
};

class VirtualMachine : public gcode::MotionSink {
 public:
  // `kin` and `job` must outlive it; `log` gets one line per feed-hold change.
  VirtualMachine(const kin::Kinematics& kin, const protocol::Job& job, PlaybackHooks hooks,
                 double speed, std::ostream& log);

  // Puts the machine at a pose (home at the start of a run) and publishes it.
  void reset(const gcode::AxisValues& joints);

  void motion(const gcode::Motion& m) override;
  void event(const gcode::Event& e) override;

  // Waits (holding the last pose) until a stop is requested.
  void holdUntilStopped();

  const ControllerState& state() const { return state_; }
  std::uint64_t motionsPlayed() const { return motions_; }
  double programSeconds() const { return program_seconds_; }  // played so far (program time)

  // Wall time between samples while playing.
  static constexpr std::chrono::milliseconds kTick{2};

 private:
  // Advances the program clock by up to `budget` seconds (program time), tick by
  // tick, honouring feed hold and stop; returns the program time that passed.
  double advance(double budget, const std::function<void(double)>& at);
  bool held();
  void checkStop() const;

  const kin::Kinematics& kin_;
  const protocol::Job& job_;
  PlaybackHooks hooks_;
  double speed_;
  std::ostream& log_;
  ControllerState state_;
  double carry_ = 0.0;  // program time already spent past the end of the last motion
  double program_seconds_ = 0.0;
  bool was_held_ = false;
  std::uint64_t motions_ = 0;
};

}  // namespace mdhd::daemon

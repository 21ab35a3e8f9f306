#include "daemon/virtual_machine.h"

#include <algorithm>
#include <ostream>
#include <thread>

#include "sim/kinematics/joint_path.h"
#include "sim/kinematics/motion_time.h"

namespace mdhd::daemon {

VirtualMachine::VirtualMachine(const kin::Kinematics& kin, const protocol::Job& job,
                               PlaybackHooks hooks, double speed, std::ostream& log)
    : kin_(kin), job_(job), hooks_(std::move(hooks)), speed_(speed), log_(log) {}

void VirtualMachine::reset(const gcode::AxisValues& joints) {
  state_ = ControllerState{};
  state_.joints = joints;
  carry_ = 0.0;
  if (hooks_.publish) hooks_.publish(state_);
}

void VirtualMachine::checkStop() const {
  if (hooks_.stop_requested && hooks_.stop_requested()) throw PlaybackStopped();
}

bool VirtualMachine::held() {
  const bool hold = hooks_.feed_hold && hooks_.feed_hold();
  if (hold != was_held_) {
    log_ << "modbus-sim: feed hold " << (hold ? "on" : "off") << " at line " << state_.line
         << std::endl;
    was_held_ = hold;
  }
  return hold;
}

double VirtualMachine::advance(double duration, const std::function<void(double)>& at) {
  // Time the previous motion overshot counts towards this one, so the program as a
  // whole keeps real time even though each motion ends on a tick.
  double t = std::min(carry_, duration);
  carry_ -= t;
  auto last = std::chrono::steady_clock::now();
  while (t < duration) {
    checkStop();
    std::this_thread::sleep_for(kTick);
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    if (held()) continue;
    t += dt * speed_;
    if (t < duration) at(t);
  }
  carry_ += t - duration;
  program_seconds_ += duration;
  return duration;
}

void VirtualMachine::motion(const gcode::Motion& m) {
  checkStop();
  const geom::Tool* tool = job_.findTool(m.tool);
  const double length = tool != nullptr ? tool->length : 0.0;
  const kin::JointPath path(kin_, m, length);
  const double duration = kin::motionSeconds(m, kin_, length);
  state_.line = m.pos.line;
  state_.tool = m.tool;
  state_.spindle_on = m.spindle != gcode::SpindleState::kOff;
  auto publish = [&](double t) {
    state_.joints = path.at(t / duration);
    if (hooks_.publish) hooks_.publish(state_);
  };
  if (duration > 0.0) advance(duration, publish);
  state_.joints = path.endJoints();
  if (hooks_.publish) hooks_.publish(state_);
  ++motions_;
}

void VirtualMachine::event(const gcode::Event& e) {
  checkStop();
  switch (e.type) {
    case gcode::EventType::kDwell:
      state_.line = e.pos.line;
      if (hooks_.publish) hooks_.publish(state_);
      advance(kin::eventSeconds(e), [](double) {});
      return;
    case gcode::EventType::kToolChange:
      state_.tool = e.tool;
      break;
    case gcode::EventType::kSpindle:
      state_.spindle_on = e.spindle != gcode::SpindleState::kOff;
      break;
    default:
      return;  // M0/M1 do not wait for an operator here; coolant and messages show nothing
  }
  state_.line = e.pos.line;
  if (hooks_.publish) hooks_.publish(state_);
}

void VirtualMachine::holdUntilStopped() {
  for (;;) {
    checkStop();
    held();  // keeps logging feed-hold changes
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace mdhd::daemon

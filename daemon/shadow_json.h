#pragma once
// The JSON of a shadow's alarms and poses, shared by its status document and its
// Server-Sent Events.
#include <cstddef>

#include <nlohmann/json.hpp>

#include "sim/check/report.h"
#include "sim/kinematics/kinematics.h"

namespace mdhd::shadow {

struct Alarm {
  bool predicted = false;
  check::Collision collision;      // depth and last_line follow the episode while it lasts
  double time_to_contact_s = 0.0;  // predicted: machine time from the pose of the prediction
  std::size_t episode = 0;         // not predicted: index among the live simulation's episodes
  std::size_t id = 0;              // index among the session's alarms (set when raised)
  // False while `collision.depth` is the first bound found when the contact opened;
  // the measured depth follows in an alarm_update event.
  bool depth_measured = true;
};

// A collision entry of the report (collisionToJson) with "id", "kind": "collision"
// or "predicted", "depth_measured" and, when predicted, "time_to_contact_s".
nlohmann::json alarmToJson(const Alarm& alarm, const kin::Machine& machine);

// {"joints": {...}, "tool_pose": {"tip": [x,y,z], "axis": [x,y,z]}} of a pose
// with a tool of `tool_length` (0: the gauge point).
nlohmann::json poseToJson(const gcode::AxisValues& joints, const kin::Kinematics& kin,
                          double tool_length);

}  // namespace mdhd::shadow

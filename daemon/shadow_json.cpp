#include "daemon/shadow_json.h"

#include "protocol/report_json.h"

namespace mdhd::shadow {
namespace {

nlohmann::json vec(const glm::dvec3& v) {
  return nlohmann::json::array({v.x, v.y, v.z});
}

}  // namespace

nlohmann::json alarmToJson(const Alarm& alarm, const kin::Machine& machine) {
  nlohmann::json j = protocol::collisionToJson(alarm.collision, &machine);
  j["id"] = alarm.id;
  j["kind"] = alarm.predicted ? "predicted" : "collision";
  j["depth_measured"] = alarm.depth_measured;
  if (alarm.predicted) j["time_to_contact_s"] = alarm.time_to_contact_s;
  return j;
}

nlohmann::json poseToJson(const gcode::AxisValues& joints, const kin::Kinematics& kin,
                          double tool_length) {
  const kin::ToolPose pose = kin.toolPose(joints, tool_length);
  return {{"joints", protocol::jointsToJson(joints, &kin.machine())},
          {"tool_pose", {{"tip", vec(pose.tip)}, {"axis", vec(pose.axis)}}}};
}

}  // namespace mdhd::shadow

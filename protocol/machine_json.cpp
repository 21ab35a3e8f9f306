#include "protocol/machine_json.h"

#include <string>
#include <vector>

namespace mdhd::protocol {
namespace {

using nlohmann::json;

using fields::fail;
using fields::number;
using fields::required;
using fields::requireObject;
using fields::string;
using fields::vec3;

kin::Limits limits(const json& j, const std::string& field) {
  if (!j.is_array() || j.size() != 2) fail(field, "an array of 2 numbers [min, max]", j);
  return {number(j[0], field + "[0]"), number(j[1], field + "[1]")};
}

kin::Joint joint(const json& j, const std::string& field) {
  requireObject(j, field, {"name", "type", "axis", "origin", "limits"});
  kin::Joint out;
  out.name = string(required(j, "name", field), field + ".name");
  const json& type = required(j, "type", field);
  if (type == "linear") {
    out.type = kin::JointType::kLinear;
  } else if (type == "rotary") {
    out.type = kin::JointType::kRotary;
  } else {
    fail(field + ".type", "\"linear\" or \"rotary\"", type);
  }
  out.axis = vec3(required(j, "axis", field), field + ".axis");
  if (j.contains("origin")) out.origin = vec3(j["origin"], field + ".origin");
  if (j.contains("limits")) out.limits = limits(j["limits"], field + ".limits");
  return out;
}

int jointByName(const kin::Machine& m, const std::string& name) {
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    if (m.joints[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::vector<int> chain(const json& j, const kin::Machine& m, const std::string& field) {
  if (!j.is_array()) fail(field, "an array of joint names", j);
  std::vector<int> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string f = field + "[" + std::to_string(i) + "]";
    const std::string name = string(j[i], f);
    const int index = jointByName(m, name);
    if (index < 0) throw FieldError(f, "unknown joint \"" + name + "\"");
    out.push_back(index);
  }
  return out;
}

void home(const json& j, kin::Machine& m, const std::string& field) {
  if (!j.is_object()) fail(field, "an object of joint values", j);
  for (const auto& [key, value] : j.items()) {
    const std::string f = field + "." + key;
    if (jointByName(m, key) < 0) throw FieldError(f, "the machine has no joint " + key);
    const double v = number(value, f);
    // A joint with a bad name is reported by validation; its home has nowhere to go.
    if (const auto axis = kin::axisOfName(key)) m.home[*axis] = v;
  }
}

json vecJson(const glm::dvec3& v) {
  return json::array({v.x, v.y, v.z});
}

}  // namespace

kin::Machine machineFromJson(const json& j, const std::string& path) {
  requireObject(j, path,
                {"name", "joints", "tool_chain", "workpiece_chain", "home", "spindle_axis",
                 "rapid_feed", "max_feed"});
  kin::Machine m;
  if (j.contains("name")) m.name = string(j["name"], path + ".name");
  const json& joints = required(j, "joints", path);
  if (!joints.is_array()) fail(path + ".joints", "an array of joints", joints);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string field = path + ".joints[" + std::to_string(i) + "]";
    kin::Joint jt = joint(joints[i], field);
    // Chains and home name joints, so a duplicate must be caught before them.
    if (const int k = jointByName(m, jt.name); k >= 0) {
      throw FieldError(field + ".name", "duplicate joint name " + jt.name + " (also joints[" +
                                            std::to_string(k) + "])");
    }
    m.joints.push_back(std::move(jt));
  }
  m.tool_chain = chain(required(j, "tool_chain", path), m, path + ".tool_chain");
  m.workpiece_chain = chain(required(j, "workpiece_chain", path), m, path + ".workpiece_chain");
  if (j.contains("home")) home(j["home"], m, path + ".home");
  m.spindle_axis = vec3(required(j, "spindle_axis", path), path + ".spindle_axis");
  m.rapid_feed = number(required(j, "rapid_feed", path), path + ".rapid_feed");
  m.max_feed = number(required(j, "max_feed", path), path + ".max_feed");
  const auto issues = kin::validateMachine(m);
  if (!issues.empty()) {
    throw FieldError(path + "." + issues.front().field, issues.front().message);
  }
  return m;
}

json machineToJson(const kin::Machine& m) {
  json joints = json::array();
  json homeJson = json::object();
  for (const kin::Joint& jt : m.joints) {
    json o = {{"name", jt.name},
              {"type", jt.type == kin::JointType::kLinear ? "linear" : "rotary"},
              {"axis", vecJson(jt.axis)}};
    if (jt.type == kin::JointType::kRotary || jt.origin != glm::dvec3(0.0)) {
      o["origin"] = vecJson(jt.origin);
    }
    if (jt.limits) o["limits"] = json::array({jt.limits->min, jt.limits->max});
    joints.push_back(std::move(o));
    if (const auto axis = kin::axisOfName(jt.name)) homeJson[jt.name] = m.home[*axis];
  }
  const auto names = [&](const std::vector<int>& chain) {
    json a = json::array();
    for (int i : chain) a.push_back(m.joints.at(static_cast<std::size_t>(i)).name);
    return a;
  };
  return {{"name", m.name},
          {"joints", std::move(joints)},
          {"tool_chain", names(m.tool_chain)},
          {"workpiece_chain", names(m.workpiece_chain)},
          {"home", std::move(homeJson)},
          {"spindle_axis", vecJson(m.spindle_axis)},
          {"rapid_feed", m.rapid_feed},
          {"max_feed", m.max_feed}};
}

}  // namespace mdhd::protocol

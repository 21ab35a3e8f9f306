#include "protocol/machine_json.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace mdhd::protocol {
namespace {

using nlohmann::json;

std::string typeName(const json& j) {
  if (j.is_number()) return "a number";
  if (j.is_string()) return "the string " + j.dump();
  if (j.is_boolean()) return j.dump();
  if (j.is_null()) return "null";
  if (j.is_array()) return "an array of " + std::to_string(j.size());
  return "an object";
}

[[noreturn]] void fail(const std::string& field, const std::string& what, const json& got) {
  throw MachineJsonError(field, "expected " + what + ", got " + typeName(got));
}

void requireObject(const json& j, const std::string& field,
                   std::initializer_list<const char*> allowed) {
  if (!j.is_object()) fail(field, "an object", j);
  for (const auto& [key, value] : j.items()) {
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      throw MachineJsonError(field + "." + key, "unknown field (known: " + list + ")");
    }
  }
}

const json& required(const json& obj, const char* key, const std::string& field) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw MachineJsonError(field + "." + key, "missing");
  return *it;
}

double number(const json& j, const std::string& field) {
  if (!j.is_number()) fail(field, "a number", j);
  return j.get<double>();
}

std::string string(const json& j, const std::string& field) {
  if (!j.is_string()) fail(field, "a string", j);
  return j.get<std::string>();
}

glm::dvec3 vec3(const json& j, const std::string& field) {
  if (!j.is_array() || j.size() != 3 ||
      !std::all_of(j.begin(), j.end(), [](const json& e) { return e.is_number(); })) {
    fail(field, "an array of 3 numbers", j);
  }
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

kin::Limits limits(const json& j, const std::string& field) {
  if (!j.is_array() || j.size() != 2 || !j[0].is_number() || !j[1].is_number()) {
    fail(field, "an array of 2 numbers [min, max]", j);
  }
  return {j[0].get<double>(), j[1].get<double>()};
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
    if (index < 0) throw MachineJsonError(f, "unknown joint \"" + name + "\"");
    out.push_back(index);
  }
  return out;
}

void home(const json& j, kin::Machine& m, const std::string& field) {
  if (!j.is_object()) fail(field, "an object of joint values", j);
  for (const auto& [key, value] : j.items()) {
    const std::string f = field + "." + key;
    if (jointByName(m, key) < 0) throw MachineJsonError(f, "the machine has no joint " + key);
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
      throw MachineJsonError(field + ".name", "duplicate joint name " + jt.name + " (also joints[" +
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
    throw MachineJsonError(path + "." + issues.front().field, issues.front().message);
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

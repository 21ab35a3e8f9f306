#include "protocol/modbus_map_json.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;
namespace f = fields;

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

RegisterType typeFromJson(const json& j, const std::string& field) {
  const std::string s = f::string(j, field);
  for (RegisterType t : {RegisterType::kFloat32, RegisterType::kInt32, RegisterType::kUint32,
                         RegisterType::kInt16, RegisterType::kUint16}) {
    if (s == registerTypeName(t)) return t;
  }
  f::fail(field, "one of float32, int32, uint32, int16, uint16", j);
}

WordOrder orderFromJson(const json& j, const std::string& field) {
  const std::string s = f::string(j, field);
  for (WordOrder o : {WordOrder::kAbcd, WordOrder::kBadc, WordOrder::kCdab, WordOrder::kDcba}) {
    if (s == wordOrderName(o)) return o;
  }
  f::fail(field, "one of abcd, badc, cdab, dcba", j);
}

RegisterField fieldFromJson(const json& j, const std::string& path) {
  f::requireObject(j, path, {"address", "type", "word_order", "scale"});
  RegisterField field;
  field.address = f::integer(f::required(j, "address", path), join(path, "address"));
  field.type = typeFromJson(f::required(j, "type", path), join(path, "type"));
  if (const json* o = f::optional(j, "word_order")) {
    field.word_order = orderFromJson(*o, join(path, "word_order"));
    if (registerCount(field.type) == 1) {
      throw FieldError(
          join(path, "word_order"),
          std::string("applies to 32-bit types only, not to ") + registerTypeName(field.type));
    }
  }
  if (const json* s = f::optional(j, "scale")) field.scale = f::number(*s, join(path, "scale"));
  return field;
}

std::vector<JointRegister> jointsFromJson(const json& j, const std::string& path) {
  if (!j.is_object()) f::fail(path, "an object of joint name -> register", j);
  std::vector<JointRegister> joints;
  for (const auto& item : j.items()) {
    const std::string p = join(path, item.key());
    const auto axis = kin::axisOfName(item.key());
    if (!axis) throw FieldError(p, "is not a joint name (X Y Z A B C U V W)");
    joints.push_back({item.key(), *axis, fieldFromJson(item.value(), p)});
  }
  return joints;
}

json fieldToJson(const RegisterField& field) {
  json j = {{"address", field.address}, {"type", registerTypeName(field.type)}};
  if (registerCount(field.type) == 2) j["word_order"] = wordOrderName(field.word_order);
  j["scale"] = field.scale;
  return j;
}

}  // namespace

ModbusMap modbusMapFromJson(const json& j, const std::string& path, const kin::Machine* machine) {
  f::requireObject(j, path,
                   {"host", "port", "unit_id", "poll_hz", "timeout_ms", "table", "joints", "tool",
                    "spindle_on", "line", "feed_hold"});
  ModbusMap map;
  map.host = f::string(f::required(j, "host", path), join(path, "host"));
  if (const json* v = f::optional(j, "port")) map.port = f::integer(*v, join(path, "port"));
  if (const json* v = f::optional(j, "unit_id"))
    map.unit_id = f::integer(*v, join(path, "unit_id"));
  if (const json* v = f::optional(j, "poll_hz")) map.poll_hz = f::number(*v, join(path, "poll_hz"));
  if (const json* v = f::optional(j, "timeout_ms")) {
    map.timeout_ms = f::integer(*v, join(path, "timeout_ms"));
  }
  if (const json* v = f::optional(j, "table")) {
    const std::string t = f::string(*v, join(path, "table"));
    if (t == "holding") {
      map.table = RegisterTable::kHolding;
    } else if (t == "input") {
      map.table = RegisterTable::kInput;
    } else {
      f::fail(join(path, "table"), "\"holding\" or \"input\"", *v);
    }
  }
  map.joints = jointsFromJson(f::required(j, "joints", path), join(path, "joints"));
  if (const json* v = f::optional(j, "tool")) map.tool = fieldFromJson(*v, join(path, "tool"));
  if (const json* v = f::optional(j, "spindle_on")) {
    map.spindle_on = fieldFromJson(*v, join(path, "spindle_on"));
  }
  if (const json* v = f::optional(j, "line")) map.line = fieldFromJson(*v, join(path, "line"));
  if (const json* v = f::optional(j, "feed_hold")) {
    const std::string p = join(path, "feed_hold");
    f::requireObject(*v, p, {"coil", "enabled"});
    map.feed_hold.coil = f::integer(f::required(*v, "coil", p), join(p, "coil"));
    if (const json* e = f::optional(*v, "enabled")) {
      map.feed_hold.enabled = f::boolean(*e, join(p, "enabled"));
    }
  }
  const auto issues = validateModbusMap(map, machine);
  if (!issues.empty()) throw FieldError(join(path, issues.front().field), issues.front().message);
  return map;
}

json modbusMapToJson(const ModbusMap& map) {
  json joints = json::object();
  for (const JointRegister& jr : map.joints) joints[jr.name] = fieldToJson(jr.field);
  json j = {{"host", map.host},
            {"port", map.port},
            {"unit_id", map.unit_id},
            {"poll_hz", map.poll_hz},
            {"timeout_ms", map.timeout_ms},
            {"table", registerTableName(map.table)},
            {"joints", joints},
            {"feed_hold", {{"coil", map.feed_hold.coil}, {"enabled", map.feed_hold.enabled}}}};
  if (map.tool) j["tool"] = fieldToJson(*map.tool);
  if (map.spindle_on) j["spindle_on"] = fieldToJson(*map.spindle_on);
  if (map.line) j["line"] = fieldToJson(*map.line);
  return j;
}

}  // namespace mdhd::protocol

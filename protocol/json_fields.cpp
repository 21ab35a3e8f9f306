#include "protocol/json_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mdhd::protocol::fields {

std::string describe(const json& j) {
  if (j.is_number()) return "the number " + j.dump();
  if (j.is_string()) return "the string " + j.dump();
  if (j.is_boolean()) return j.dump();
  if (j.is_null()) return "null";
  if (j.is_array()) return "an array of " + std::to_string(j.size());
  return "an object";
}

void fail(const std::string& field, const std::string& expected, const json& got) {
  throw FieldError(field, "expected " + expected + ", got " + describe(got));
}

void requireObject(const json& j, const std::string& field,
                   std::initializer_list<const char*> allowed) {
  if (!j.is_object()) fail(field, "an object", j);
  for (const auto& item : j.items()) {
    const std::string& key = item.key();
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) {
      std::string known;
      for (const char* a : allowed) known += std::string(known.empty() ? "" : ", ") + a;
      throw FieldError(field.empty() ? key : field + "." + key,
                       "unknown field (known: " + known + ")");
    }
  }
}

const json& required(const json& object, const char* key, const std::string& field) {
  const auto it = object.find(key);
  if (it == object.end()) throw FieldError(field.empty() ? key : field + "." + key, "missing");
  return *it;
}

const json* optional(const json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

double number(const json& j, const std::string& field) {
  if (!j.is_number()) fail(field, "a number", j);
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(field, "a finite number", j);
  return v;
}

double positive(const json& j, const std::string& field) {
  const double v = number(j, field);
  if (!(v > 0.0)) fail(field, "a number > 0", j);
  return v;
}

int integer(const json& j, const std::string& field) {
  if (!j.is_number()) fail(field, "an integer", j);
  const double v = j.get<double>();
  if (v != std::floor(v) || std::abs(v) > std::numeric_limits<int>::max()) {
    fail(field, "an integer", j);
  }
  return static_cast<int>(v);
}

bool boolean(const json& j, const std::string& field) {
  if (!j.is_boolean()) fail(field, "true or false", j);
  return j.get<bool>();
}

std::string string(const json& j, const std::string& field) {
  if (!j.is_string()) fail(field, "a string", j);
  return j.get<std::string>();
}

glm::dvec3 vec3(const json& j, const std::string& field) {
  if (!j.is_array() || j.size() != 3) fail(field, "an array of 3 numbers", j);
  return {number(j[0], field + "[0]"), number(j[1], field + "[1]"), number(j[2], field + "[2]")};
}

}  // namespace mdhd::protocol::fields

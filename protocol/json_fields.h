#pragma once
// Strict reading of JSON documents field by field: every error names the field's
// path in the document ("tools[1].corner_radius") and says what was expected.
#include <initializer_list>
#include <stdexcept>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace mdhd::protocol {

class FieldError : public std::runtime_error {
 public:
  FieldError(std::string field, const std::string& message)
      : std::runtime_error(field + ": " + message), field_(std::move(field)), message_(message) {}
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }

 private:
  std::string field_;
  std::string message_;
};

namespace fields {

using nlohmann::json;

// "a number", "the string \"x\"", "an array of 2", ... for error messages.
std::string describe(const json& j);
[[noreturn]] void fail(const std::string& field, const std::string& expected, const json& got);

// `j` must be an object whose keys are all in `allowed`.
void requireObject(const json& j, const std::string& field,
                   std::initializer_list<const char*> allowed);
const json& required(const json& object, const char* key, const std::string& field);
const json* optional(const json& object, const char* key);  // null when absent

double number(const json& j, const std::string& field);
double positive(const json& j, const std::string& field);  // > 0
int integer(const json& j, const std::string& field);
bool boolean(const json& j, const std::string& field);
std::string string(const json& j, const std::string& field);
glm::dvec3 vec3(const json& j, const std::string& field);

}  // namespace fields
}  // namespace mdhd::protocol

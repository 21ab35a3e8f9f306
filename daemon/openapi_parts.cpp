#include "daemon/openapi_parts.h"

namespace mdhd::service {
namespace {

void rewriteRefs(nlohmann::json& j, const std::string& prefix) {
  if (j.is_object()) {
    for (auto& [key, value] : j.items()) {
      if (key == "$ref" && value.is_string()) {
        const std::string ref = value.get<std::string>();
        const std::string local = "#/$defs/";
        if (ref.rfind(local, 0) == 0) {
          value = "#/components/schemas/" + prefix + ref.substr(local.size());
        }
      } else {
        rewriteRefs(value, prefix);
      }
    }
  } else if (j.is_array()) {
    for (auto& value : j) rewriteRefs(value, prefix);
  }
}

}  // namespace

nlohmann::json jsonResponse(const std::string& description, const nlohmann::json& schema) {
  return {{"description", description}, {"content", {{"application/json", {{"schema", schema}}}}}};
}

nlohmann::json errorResponse(const std::string& description) {
  return jsonResponse(description, schemaRef("Error"));
}

nlohmann::json schemaRef(const std::string& name) {
  return {{"$ref", "#/components/schemas/" + name}};
}

nlohmann::json errorSchema() {
  return {{"type", "object"},
          {"required", {"error"}},
          {"properties",
           {{"error",
             {{"type", "object"},
              {"required", {"code", "message"}},
              {"properties",
               {{"code", {{"type", "string"}}},
                {"message", {{"type", "string"}}},
                {"field", {{"type", "string"}, {"description", "The JSON path at fault."}}},
                {"line", {{"type", "integer"}, {"description", "Program line (422)."}}},
                {"column", {{"type", "integer"}, {"description", "Program column (422)."}}}}}}}}}};
}

nlohmann::json schemaComponents(const std::string& name, const std::string& prefix,
                                nlohmann::json schema) {
  nlohmann::json out = nlohmann::json::object();
  if (schema.contains("$defs")) {
    for (auto& [def, body] : schema["$defs"].items()) {
      nlohmann::json copy = body;
      rewriteRefs(copy, prefix);
      out[prefix + def] = std::move(copy);
    }
    schema.erase("$defs");
  }
  schema.erase("$schema");
  schema.erase("$id");
  rewriteRefs(schema, prefix);
  out[name] = std::move(schema);
  return out;
}

}  // namespace mdhd::service

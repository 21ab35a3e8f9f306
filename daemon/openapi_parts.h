#pragma once
// Small builders for the OpenAPI operation objects the route files register.
#include <string>

#include <nlohmann/json.hpp>

namespace mdhd::service {

// {"description", "content": {"application/json": {"schema": schema}}}
nlohmann::json jsonResponse(const std::string& description, const nlohmann::json& schema);
// A response whose body is the error document.
nlohmann::json errorResponse(const std::string& description);
// {"$ref": "#/components/schemas/<name>"}
nlohmann::json schemaRef(const std::string& name);
// The schema of the error document.
nlohmann::json errorSchema();

// A JSON Schema (2020-12, with "$defs" and "#/$defs/x" refs) as OpenAPI
// components: each def becomes "<prefix><Def>" and its refs are rewritten; the
// schema itself becomes `name`. Returned as {name: schema, prefix+def: ...}.
nlohmann::json schemaComponents(const std::string& name, const std::string& prefix,
                                nlohmann::json schema);

}  // namespace mdhd::service

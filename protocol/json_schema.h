#pragma once
// A small JSON Schema validator (the draft 2020-12 keywords the project's schemas
// use) and the project's schemas, embedded in the binary so the service can
// serve them. Keywords: type, properties, required, additionalProperties, items,
// prefixItems, minItems, maxItems, minProperties, enum, const, minimum, maximum,
// exclusiveMinimum, exclusiveMaximum, minLength, pattern, oneOf, anyOf, allOf,
// $ref to "#/$defs/<name>"; annotations ($schema, $id, title, description,
// default, examples, $comment, $defs) are read and ignored. A schema that uses
// any other keyword is refused, so nothing is silently not checked.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace mdhd::protocol {

// One place where a document breaks its schema: `path` in the job's spelling
// ("tools[1].diameter", "(document)" for the root) and what is wrong there.
struct SchemaProblem {
  std::string path;
  std::string message;
};

class JsonSchema {
 public:
  // Throws std::invalid_argument naming the place of an unknown keyword, a $ref
  // that does not resolve or a keyword with a value of the wrong kind.
  explicit JsonSchema(nlohmann::json schema);

  // Every problem found (at most `max_problems`), in document order; empty: valid.
  std::vector<SchemaProblem> validate(const nlohmann::json& doc,
                                      std::size_t max_problems = 20) const;

  const nlohmann::json& document() const { return schema_; }

 private:
  void checkSchema(const nlohmann::json& s, const std::string& where) const;
  void check(const nlohmann::json& s, const nlohmann::json& v, const std::string& path,
             std::vector<SchemaProblem>& out, int depth) const;
  const nlohmann::json& resolve(const std::string& ref) const;

  nlohmann::json schema_;
};

// The embedded schema texts (protocol/schemas/*.schema.json) and their validators.
std::string_view jobSchemaText();
std::string_view reportSchemaText();
const JsonSchema& jobSchema();
const JsonSchema& reportSchema();

}  // namespace mdhd::protocol

#include "protocol/json_schema.h"

#include <cmath>
#include <regex>
#include <set>

#include "protocol/json_fields.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;

constexpr int kMaxDepth = 64;  // $ref chains and nesting: a cycle must not recurse forever

const std::set<std::string> kKeywords{"type",
                                      "properties",
                                      "required",
                                      "additionalProperties",
                                      "items",
                                      "prefixItems",
                                      "minItems",
                                      "maxItems",
                                      "minProperties",
                                      "enum",
                                      "const",
                                      "minimum",
                                      "maximum",
                                      "exclusiveMinimum",
                                      "exclusiveMaximum",
                                      "minLength",
                                      "pattern",
                                      "oneOf",
                                      "anyOf",
                                      "allOf",
                                      "$ref"};
const std::set<std::string> kAnnotations{"$schema", "$id",      "title",    "description",
                                         "default", "examples", "$comment", "$defs"};

std::string child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

bool isType(const json& v, const std::string& type) {
  if (type == "object") return v.is_object();
  if (type == "array") return v.is_array();
  if (type == "string") return v.is_string();
  if (type == "boolean") return v.is_boolean();
  if (type == "null") return v.is_null();
  if (type == "number") return v.is_number();
  if (type == "integer") {
    if (v.is_number_integer()) return true;
    if (!v.is_number_float()) return false;
    const double d = v.get<double>();
    return std::isfinite(d) && std::floor(d) == d;
  }
  return false;
}

std::string typeList(const json& t) {
  if (t.is_string()) return t.get<std::string>();
  std::string s;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (i > 0) s += i + 1 == t.size() ? " or " : ", ";
    s += t[i].get<std::string>();
  }
  return s;
}

std::string article(const std::string& type) {
  return (type == "object" || type == "array" || type == "integer" ? "an " : "a ") + type;
}

std::string shown(const json& v) {
  std::string s = v.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

}  // namespace

JsonSchema::JsonSchema(json schema) : schema_(std::move(schema)) {
  checkSchema(schema_, "#");
  if (schema_.contains("$defs")) {
    if (!schema_["$defs"].is_object()) throw std::invalid_argument("#/$defs: must be an object");
    for (const auto& [name, s] : schema_["$defs"].items()) checkSchema(s, "#/$defs/" + name);
  }
}

const json& JsonSchema::resolve(const std::string& ref) const {
  static const std::string kPrefix = "#/$defs/";
  if (ref.rfind(kPrefix, 0) != 0)
    throw std::invalid_argument("$ref " + ref + ": only #/$defs/<name>");
  const std::string name = ref.substr(kPrefix.size());
  if (!schema_.contains("$defs") || !schema_["$defs"].contains(name))
    throw std::invalid_argument("$ref " + ref + ": no such definition");
  return schema_["$defs"][name];
}

void JsonSchema::checkSchema(const json& s, const std::string& where) const {
  if (s.is_boolean()) return;
  if (!s.is_object())
    throw std::invalid_argument(where + ": a schema must be an object or boolean");
  for (const auto& [key, value] : s.items()) {
    const std::string at = where + "/" + key;
    if (kAnnotations.count(key) != 0) continue;
    if (kKeywords.count(key) == 0) throw std::invalid_argument(at + ": unsupported keyword");
    if (key == "properties") {
      if (!value.is_object()) throw std::invalid_argument(at + ": must be an object");
      for (const auto& [name, sub] : value.items()) checkSchema(sub, at + "/" + name);
    } else if (key == "items" || key == "additionalProperties") {
      checkSchema(value, at);
    } else if (key == "prefixItems" || key == "oneOf" || key == "anyOf" || key == "allOf") {
      if (!value.is_array() || value.empty())
        throw std::invalid_argument(at + ": must be a non-empty array");
      for (std::size_t i = 0; i < value.size(); ++i)
        checkSchema(value[i], at + "/" + std::to_string(i));
    } else if (key == "required") {
      if (!value.is_array()) throw std::invalid_argument(at + ": must be an array of names");
      for (const json& n : value)
        if (!n.is_string()) throw std::invalid_argument(at + ": must be an array of names");
    } else if (key == "enum") {
      if (!value.is_array() || value.empty())
        throw std::invalid_argument(at + ": must be a non-empty array");
    } else if (key == "type") {
      const json list = value.is_array() ? value : json::array({value});
      for (const json& t : list) {
        static const std::set<std::string> kTypes{"object", "array",   "string", "boolean",
                                                  "null",   "integer", "number"};
        if (!t.is_string() || kTypes.count(t.get<std::string>()) == 0)
          throw std::invalid_argument(at + ": unknown type " + t.dump());
      }
    } else if (key == "$ref") {
      if (!value.is_string()) throw std::invalid_argument(at + ": must be a string");
      resolve(value.get<std::string>());
    } else if (key == "pattern") {
      if (!value.is_string()) throw std::invalid_argument(at + ": must be a string");
      try {
        std::regex re(value.get<std::string>(), std::regex::ECMAScript);
      } catch (const std::regex_error&) {
        throw std::invalid_argument(at + ": not a valid regular expression");
      }
    } else if (key != "const") {
      if (!value.is_number()) throw std::invalid_argument(at + ": must be a number");
    }
  }
}

std::vector<SchemaProblem> JsonSchema::validate(const json& doc, std::size_t max_problems) const {
  std::vector<SchemaProblem> out;
  check(schema_, doc, "", out, 0);
  for (SchemaProblem& p : out)
    if (p.path.empty()) p.path = "(document)";
  if (out.size() > max_problems) out.resize(max_problems);
  return out;
}

void JsonSchema::check(const json& s, const json& v, const std::string& path,
                       std::vector<SchemaProblem>& out, int depth) const {
  auto fail = [&](const std::string& where, const std::string& message) {
    out.push_back({where, message});
  };
  if (depth > kMaxDepth) return fail(path, "schema nesting too deep");
  if (s.is_boolean()) {
    if (!s.get<bool>()) fail(path, "not allowed here");
    return;
  }
  if (const auto it = s.find("$ref"); it != s.end()) check(resolve(*it), v, path, out, depth + 1);
  if (const auto it = s.find("type"); it != s.end()) {
    const json list = it->is_array() ? *it : json::array({*it});
    bool ok = false;
    for (const json& t : list) ok = ok || isType(v, t.get<std::string>());
    if (!ok) {
      const std::string want =
          list.size() == 1 ? article(list[0].get<std::string>()) : typeList(*it);
      return fail(path, "expected " + want + ", got " + fields::describe(v));
    }
  }
  if (const auto it = s.find("const"); it != s.end() && v != *it)
    fail(path, "must be " + it->dump());
  if (const auto it = s.find("enum"); it != s.end()) {
    bool found = false;
    std::string list;
    for (const json& e : *it) {
      found = found || e == v;
      list += (list.empty() ? "" : ", ") + e.dump();
    }
    if (!found) fail(path, "must be one of " + list + ", got " + shown(v));
  }
  if (v.is_number()) {
    const double x = v.get<double>();
    auto bound = [&](const char* key, auto bad, const char* words) {
      if (const auto it = s.find(key); it != s.end() && bad(x, it->template get<double>()))
        fail(path, std::string("must be ") + words + " " + it->dump() + ", got " + shown(v));
    };
    bound(
        "minimum", [](double a, double b) { return a < b; }, ">=");
    bound(
        "maximum", [](double a, double b) { return a > b; }, "<=");
    bound(
        "exclusiveMinimum", [](double a, double b) { return a <= b; }, ">");
    bound(
        "exclusiveMaximum", [](double a, double b) { return a >= b; }, "<");
  }
  if (v.is_string()) {
    const std::string& str = v.get_ref<const std::string&>();
    if (const auto it = s.find("minLength"); it != s.end() && str.size() < it->get<std::size_t>())
      fail(path, "must have at least " + it->dump() + " characters");
    if (const auto it = s.find("pattern"); it != s.end()) {
      const std::regex re(it->get<std::string>(), std::regex::ECMAScript);
      if (!std::regex_search(str, re)) fail(path, "must match " + it->dump() + ", got " + shown(v));
    }
  }
  if (v.is_object()) {
    if (const auto it = s.find("minProperties"); it != s.end() && v.size() < it->get<std::size_t>())
      fail(path, "must have at least " + it->dump() + " member(s)");
    if (const auto it = s.find("required"); it != s.end()) {
      for (const json& name : *it)
        if (!v.contains(name.get<std::string>()))
          fail(child(path, name.get<std::string>()), "missing (required)");
    }
    const auto props = s.find("properties");
    const auto extra = s.find("additionalProperties");
    for (const auto& [key, value] : v.items()) {
      if (props != s.end() && props->contains(key)) {
        check((*props)[key], value, child(path, key), out, depth + 1);
      } else if (extra != s.end()) {
        if (extra->is_boolean() && !extra->get<bool>()) {
          std::string known;
          if (props != s.end())
            for (const auto& [name, unused] : props->items())
              known += (known.empty() ? "" : " ") + name;
          fail(child(path, key),
               "unknown field" + (known.empty() ? "" : " (known: " + known + ")"));
        } else {
          check(*extra, value, child(path, key), out, depth + 1);
        }
      }
    }
  }
  if (v.is_array()) {
    if (const auto it = s.find("minItems"); it != s.end() && v.size() < it->get<std::size_t>())
      fail(path, "must have at least " + it->dump() + " item(s), got " + std::to_string(v.size()));
    if (const auto it = s.find("maxItems"); it != s.end() && v.size() > it->get<std::size_t>())
      fail(path, "must have at most " + it->dump() + " item(s), got " + std::to_string(v.size()));
    std::size_t first = 0;
    if (const auto it = s.find("prefixItems"); it != s.end()) {
      for (; first < it->size() && first < v.size(); ++first)
        check((*it)[first], v[first], index(path, first), out, depth + 1);
    }
    if (const auto it = s.find("items"); it != s.end()) {
      for (std::size_t i = first; i < v.size(); ++i)
        check(*it, v[i], index(path, i), out, depth + 1);
    }
  }
  if (const auto it = s.find("allOf"); it != s.end()) {
    for (const json& sub : *it) check(sub, v, path, out, depth + 1);
  }
  for (const char* key : {"oneOf", "anyOf"}) {
    const auto it = s.find(key);
    if (it == s.end()) continue;
    std::vector<std::vector<SchemaProblem>> branches;
    int matched = 0;
    for (const json& sub : *it) {
      branches.emplace_back();
      check(sub, v, path, branches.back(), depth + 1);
      matched += branches.back().empty();
    }
    const bool one = std::string(key) == "oneOf";
    if (matched == 0) {
      // An alternative that accepted the shape and failed inside it (not on a missing
      // or unknown member) is the one the author meant: its problems say the most.
      std::size_t best = 0, bestLen = 0;
      bool tie = false;
      for (std::size_t i = 0; i < branches.size(); ++i) {
        std::size_t len = 0;
        for (const SchemaProblem& p : branches[i]) {
          const bool structural =
              p.message == "missing (required)" || p.message.rfind("unknown field", 0) == 0;
          if (!structural) len = std::max(len, p.path.size() + 1);
        }
        if (len > bestLen) {
          tie = false;
          best = i;
          bestLen = len;
        } else if (len == bestLen && len > 0) {
          tie = true;
        }
      }
      if (!tie && bestLen > path.size() + 1) {
        out.insert(out.end(), branches[best].begin(), branches[best].end());
      } else {
        std::string why;
        for (const auto& b : branches)
          why += (why.empty() ? "" : "; or ") + (b.front().path == path || b.front().path.empty()
                                                     ? b.front().message
                                                     : b.front().path + ": " + b.front().message);
        fail(path,
             "matches none of the " + std::to_string(branches.size()) + " alternatives: " + why);
      }
    } else if (one && matched > 1) {
      fail(path,
           "matches " + std::to_string(matched) + " alternatives where exactly one must match");
    }
  }
}

const JsonSchema& jobSchema() {
  static const JsonSchema schema(json::parse(jobSchemaText()));
  return schema;
}

const JsonSchema& reportSchema() {
  static const JsonSchema schema(json::parse(reportSchemaText()));
  return schema;
}

}  // namespace mdhd::protocol

#include "daemon/http_errors.h"

#include <httplib.h>

#include <algorithm>
#include <cctype>

#include "daemon/number_text.h"
#include "protocol/job_json.h"

namespace mdhd::service {

nlohmann::json errorBody(const HttpError& e) {
  nlohmann::json error = {{"code", e.code()}, {"message", e.what()}};
  if (e.extra().is_object()) {
    for (const auto& [key, value] : e.extra().items()) error[key] = value;
  }
  return {{"error", error}};
}

void sendJsonText(httplib::Response& res, int status, std::string text) {
  res.status = status;
  text += '\n';
  res.set_content(std::move(text), "application/json");
}

void sendJson(httplib::Response& res, int status, const nlohmann::json& body) {
  sendJsonText(res, status, body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

void sendError(httplib::Response& res, const HttpError& e) {
  sendJson(res, e.status(), errorBody(e));
}

namespace {

// Deepest nesting of arrays and objects in a JSON text (strings skipped), so a
// hostile body cannot drive the recursive walks after parsing too deep.
int nestingDepth(const std::string& text) {
  int depth = 0;
  int deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

constexpr int kMaxNesting = 64;

// "application/json", in any case, with or without parameters ("; charset=utf-8").
bool isJsonMediaType(const std::string& type) {
  std::string media = type.substr(0, type.find(';'));
  while (!media.empty() && (media.back() == ' ' || media.back() == '\t')) media.pop_back();
  const std::size_t start = media.find_first_not_of(" \t");
  if (start == std::string::npos) return false;
  media.erase(0, start);
  for (char& c : media) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return media == "application/json";
}

}  // namespace

nlohmann::json parseJsonBody(const httplib::Request& req) {
  const std::string type = req.get_header_value("Content-Type");
  if (!type.empty() && !isJsonMediaType(type)) {
    throw HttpError(415, "unsupported_media_type",
                    "the body must be application/json, not " + type);
  }
  if (req.body.empty()) throw HttpError(400, "bad_json", "the request needs a JSON body");
  if (nestingDepth(req.body) > kMaxNesting) {
    throw HttpError(400, "bad_json",
                    "JSON nested deeper than " + std::to_string(kMaxNesting) + " levels");
  }
  try {
    return protocol::parseJsonText(req.body);
  } catch (const protocol::FieldError& e) {
    throw HttpError(400, "bad_json", e.message());
  }
}

long long queryInteger(const httplib::Request& req, const char* name, long long fallback,
                       long long lo, long long hi) {
  if (!req.has_param(name)) return fallback;
  const std::optional<long long> v = integerInRange(req.get_param_value(name), lo, hi);
  if (!v) {
    throw HttpError(400, "bad_parameter",
                    std::string(name) + ": expected an integer from " + std::to_string(lo) +
                        " to " + std::to_string(hi),
                    {{"parameter", name}});
  }
  return *v;
}

}  // namespace mdhd::service

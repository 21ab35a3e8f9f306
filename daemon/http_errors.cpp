#include "daemon/http_errors.h"

#include <httplib.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string_view>

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
    if (e.field() == "(document)") throw HttpError(400, "bad_json", e.message());
    throw HttpError(400, "bad_json", e.what(), {{"field", e.field()}});  // a repeated key
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

void checkQueryParameters(const httplib::Request& req,
                          std::initializer_list<std::string_view> known) {
  std::string names;
  for (std::string_view k : known) names += (names.empty() ? "" : ", ") + std::string(k);
  for (const auto& [name, value] : req.params) {
    const std::string shown = name.substr(0, 64);
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw HttpError(400, "bad_parameter",
                      "unknown query parameter " + shown + " (known: " + names + ")",
                      {{"parameter", shown}});
    }
    if (req.get_param_value_count(name.c_str()) > 1) {
      throw HttpError(400, "bad_parameter", name + ": given more than once", {{"parameter", name}});
    }
  }
}

namespace {

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

}  // namespace

std::optional<ByteRange> requestedByteRange(const httplib::Request& req, httplib::Response& res,
                                            std::uint64_t size) {
  if (!req.has_header("Range") || req.has_header("If-Range")) return std::nullopt;
  const std::string value = req.get_header_value("Range");
  const std::size_t eq = value.find('=');
  if (eq == std::string::npos) return std::nullopt;
  std::string unit(trimmed(std::string_view(value).substr(0, eq)));
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string_view spec = trimmed(std::string_view(value).substr(eq + 1));
  if (unit != "bytes" || spec.find(',') != std::string_view::npos) return std::nullopt;
  const std::size_t dash = spec.find('-');
  if (dash == std::string_view::npos) return std::nullopt;
  const std::string_view firstText = spec.substr(0, dash);
  const std::string_view lastText = spec.substr(dash + 1);
  ByteRange range;
  bool satisfiable = false;
  if (firstText.empty()) {  // "-N": the last N bytes
    const auto n = decimalDigits(lastText, 19);
    if (!n) return std::nullopt;
    satisfiable = *n > 0 && size > 0;
    range = {size > *n ? size - *n : 0, size > 0 ? size - 1 : 0};
  } else {
    const auto first = decimalDigits(firstText, 19);
    const auto last =
        lastText.empty() ? std::optional<std::uint64_t>(UINT64_MAX) : decimalDigits(lastText, 19);
    if (!first || !last || *last < *first) return std::nullopt;
    satisfiable = *first < size;
    range = {*first, std::min(*last, size > 0 ? size - 1 : 0)};
  }
  if (!satisfiable) {
    res.set_header("Content-Range", "bytes */" + std::to_string(size));
    throw HttpError(416, "range_not_satisfiable",
                    "the range " + std::string(spec.substr(0, 64)) + " is outside the " +
                        std::to_string(size) + " bytes",
                    {{"size", size}});
  }
  return range;
}

}  // namespace mdhd::service

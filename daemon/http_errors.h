#pragma once
// Errors of the HTTP API: {"error": {"code", "message", ...}} with a status of
// the contract. A route handler throws HttpError; the service turns it into the
// reply (and anything else it throws into a 500 that says nothing internal).
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace mdhd::service {

class HttpError : public std::runtime_error {
 public:
  // `extra` fields (an object) go into the error object beside code and message.
  HttpError(int status, std::string code, const std::string& message,
            nlohmann::json extra = nlohmann::json::object())
      : std::runtime_error(message),
        status_(status),
        code_(std::move(code)),
        extra_(std::move(extra)) {}
  int status() const { return status_; }
  const std::string& code() const { return code_; }
  const nlohmann::json& extra() const { return extra_; }

 private:
  int status_;
  std::string code_;
  nlohmann::json extra_;
};

// The error document for `e`.
nlohmann::json errorBody(const HttpError& e);

// Replies with `body` as application/json.
void sendJson(httplib::Response& res, int status, const nlohmann::json& body);
// Replies with an already serialised JSON text.
void sendJsonText(httplib::Response& res, int status, std::string text);
void sendError(httplib::Response& res, const HttpError& e);

// The request body as JSON: 415 when it is declared as something else, 400 with
// line and column when it does not parse.
nlohmann::json parseJsonBody(const httplib::Request& req);

// A query parameter as an integer in [lo, hi] (400 otherwise), or `fallback`.
long long queryInteger(const httplib::Request& req, const char* name, long long fallback,
                       long long lo, long long hi);

// 400 `bad_parameter` for a query parameter not in `known` or given twice: an
// `offset` or a `status` filter the route does not have must not be ignored (a
// script paging by offset got the first page again and again).
void checkQueryParameters(const httplib::Request& req,
                          std::initializer_list<std::string_view> known);

// The one byte range a GET asks for with `Range: bytes=...` (RFC 9110 14.2), as
// [first, last] of a body of `size` bytes. None: serve the whole body (no Range,
// an If-Range (the service sends no validators), several ranges, another unit, a
// malformed one). A range that starts at or past the end is 416
// `range_not_satisfiable`, with `Content-Range: bytes */size` set on `res`.
struct ByteRange {
  std::uint64_t first = 0;
  std::uint64_t last = 0;
};
std::optional<ByteRange> requestedByteRange(const httplib::Request& req, httplib::Response& res,
                                            std::uint64_t size);

}  // namespace mdhd::service

#include "daemon/auth.h"

#include <httplib.h>

#include <cctype>
#include <string_view>

#include "daemon/http_errors.h"

namespace mdhd::service {

bool constantTimeEqual(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  const std::size_t n = std::max(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char x = i < a.size() ? static_cast<unsigned char>(a[i]) : 0;
    const unsigned char y = i < b.size() ? static_cast<unsigned char>(b[i]) : 0;
    diff |= x ^ y;
  }
  return diff == 0;
}

void Auth::check(const httplib::Request& req) const {
  if (tokens_.empty()) return;
  if (!req.has_header("Authorization")) {
    throw HttpError(401, "unauthorized", "this service needs an Authorization: Bearer token");
  }
  const std::string value = req.get_header_value("Authorization");
  // The scheme is case-insensitive (RFC 9110 11.1), then one or more spaces.
  constexpr std::string_view kScheme = "bearer";
  bool bearer = value.size() > kScheme.size() && value[kScheme.size()] == ' ';
  for (std::size_t i = 0; bearer && i < kScheme.size(); ++i) {
    bearer = std::tolower(static_cast<unsigned char>(value[i])) == kScheme[i];
  }
  const std::size_t start = bearer ? value.find_first_not_of(' ', kScheme.size()) : 0;
  if (!bearer || start == std::string::npos) {
    throw HttpError(401, "unauthorized", "the Authorization header must be 'Bearer <token>'");
  }
  const std::string token = value.substr(start);
  bool accepted = false;
  for (const std::string& t : tokens_) accepted |= constantTimeEqual(token, t);
  if (!accepted) throw HttpError(403, "forbidden", "the bearer token is not accepted");
}

}  // namespace mdhd::service

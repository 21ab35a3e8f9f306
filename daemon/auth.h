#pragma once
// Bearer-token authentication: "Authorization: Bearer <token>" against the
// configured tokens. No tokens configured (allowed on loopback only): open.
#include <string>
#include <vector>

namespace httplib {
struct Request;
}

namespace mdhd::service {

class Auth {
 public:
  explicit Auth(std::vector<std::string> tokens) : tokens_(std::move(tokens)) {}
  bool enabled() const { return !tokens_.empty(); }
  // Throws HttpError 401 (no or malformed credentials) or 403 (a token not accepted).
  void check(const httplib::Request& req) const;

 private:
  std::vector<std::string> tokens_;
};

// Compares in time independent of where the texts differ.
bool constantTimeEqual(const std::string& a, const std::string& b);

}  // namespace mdhd::service

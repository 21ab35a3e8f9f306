#include "daemon/http_service.h"

#include <httplib.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "daemon/guarded_server.h"
#include "daemon/http_errors.h"
#include "daemon/number_text.h"
#include "daemon/openapi_parts.h"

namespace mdhd::service {
namespace {

using Clock = std::chrono::steady_clock;

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  }
  return true;
}

std::vector<std::string> splitPath(const std::string& path) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i <= path.size()) {
    const std::size_t slash = std::min(path.find('/', i), path.size());
    out.push_back(path.substr(i, slash - i));
    i = slash + 1;
  }
  return out;
}

// Whether `path` matches a template's segments (as pathPattern's regex would).
bool segmentsMatch(const std::vector<std::string>& templ, const std::string& path) {
  std::size_t i = 0;
  for (const std::string& t : templ) {
    if (i > path.size()) return false;
    const std::size_t slash = std::min(path.find('/', i), path.size());
    const std::string_view seg(path.data() + i, slash - i);
    if (!t.empty() && t.front() == '{' && t.back() == '}') {
      if (seg.empty()) return false;
    } else if (seg != t) {
      return false;
    }
    i = slash + 1;
  }
  return i == path.size() + 1;
}

// A Content-Length value: digits only (no sign, no spaces), at most 18 of them.
std::optional<std::uint64_t> contentLength(const std::string& text) {
  return decimalDigits(text, 18);
}

// What a route's method adds to an Allow list so far: GET brings HEAD, which every
// GET route answers.
std::string allowedMethods(const std::string& sofar, const std::string& method) {
  const std::string sep = sofar.empty() ? "" : ", ";
  return method == "GET" ? sep + "GET, HEAD" : sep + method;
}

std::string regexEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (std::string_view(".^$|()[]{}*+?\\").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string pathPattern(const std::string& path) {
  std::string out;
  std::size_t i = 0;
  while (i < path.size()) {
    const std::size_t open = path.find('{', i);
    if (open == std::string::npos) {
      out += regexEscape(path.substr(i));
      break;
    }
    const std::size_t close = path.find('}', open);
    if (close == std::string::npos) throw std::invalid_argument("unclosed { in " + path);
    out += regexEscape(path.substr(i, open - i)) + "([^/]+)";
    i = close + 1;
  }
  return out;
}

std::string pathParam(const httplib::Request& req, std::size_t i) {
  if (i >= req.matches.size()) return "";
  return req.matches[static_cast<int>(i)].str();  // httplib decoded the path already
}

HttpService::HttpService(HttpSettings settings, JsonLog& log, Metrics& metrics)
    : settings_(std::move(settings)),
      log_(log),
      metrics_(metrics),
      auth_(settings_.tokens),
      server_(makeGuardedServer(settings_.head_timeout, settings_.max_head_bytes,
                                settings_.max_body_bytes)) {
  const int threads = settings_.threads;
  server_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server_->set_tcp_nodelay(true);  // else Nagle adds tens of ms to keep-alive replies
  // SO_REUSEADDR only: the library's default adds SO_REUSEPORT, with which a second
  // service binds the same port and the kernel splits the clients between the two.
  server_->set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  server_->set_payload_max_length(settings_.max_body_bytes);
  server_->set_read_timeout(10, 0);
  server_->set_write_timeout(10, 0);
  server_->set_keep_alive_timeout(5);
  server_->set_keep_alive_max_count(1000);
  server_->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    return screen(req, res) ? httplib::Server::HandlerResponse::Handled
                            : httplib::Server::HandlerResponse::Unhandled;
  });
  // `Expect: 100-continue`: the library would invite the body ("100 Continue") before
  // the screen runs, so a client asked first and was sent the 413 only after
  // uploading. The screen answers instead; a request it passes is screened again
  // (harmlessly) on routing.
  server_->set_expect_100_continue_handler(
      [this](const httplib::Request& req, httplib::Response& res) {
        if (!screen(req, res)) return 100;
        // The library writes this reply without a length of its own.
        res.set_header("Content-Length", std::to_string(res.body.size()));
        return res.status;
      });
  server_->set_error_handler(httplib::Server::HandlerWithResponse(
      [this](const httplib::Request& req, httplib::Response& res) {
        // Called for every reply >= 400; route handlers have filled theirs already.
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        handleUnrouted(req, res);
        return httplib::Server::HandlerResponse::Handled;
      }));
}

HttpService::~HttpService() {
  stop();
}

void HttpService::route(Route route, Handler handler) {
  const std::string pattern = pathPattern(route.path);
  const std::string label = route.path;
  const bool needsAuth = route.auth;
  auto wrapped = [this, label, needsAuth, handler = std::move(handler)](const httplib::Request& req,
                                                                        httplib::Response& res) {
    const Clock::time_point started = Clock::now();
    try {
      if (needsAuth) auth_.check(req);
      if (req.body.size() > settings_.max_body_bytes) {  // a chunked body's framing slack
        throw HttpError(413, "body_too_large",
                        "the body is larger than the limit of " +
                            std::to_string(settings_.max_body_bytes) + " bytes");
      }
      handler(req, res);
    } catch (const HttpError& e) {
      if (e.status() == 401) res.set_header("WWW-Authenticate", "Bearer");
      sendError(res, e);
    } catch (const std::exception& e) {
      log_.write("internal_error", {{"route", label}, {"what", e.what()}});
      sendError(res, HttpError(500, "internal", "the service failed on this request"));
    }
    record(label, req, res, std::chrono::duration<double>(Clock::now() - started).count());
  };
  const std::string& m = route.method;
  if (m == "GET") {
    server_->Get(pattern, wrapped);
  } else if (m == "POST") {
    server_->Post(pattern, wrapped);
  } else if (m == "PUT") {
    server_->Put(pattern, wrapped);
  } else if (m == "DELETE") {
    server_->Delete(pattern, wrapped);
  } else if (m == "PATCH") {
    server_->Patch(pattern, wrapped);
  } else {
    throw std::invalid_argument("unsupported method " + m);
  }
  std::vector<std::string> segments = splitPath(route.path);
  routes_.push_back({std::move(route), std::regex(pattern), std::move(segments)});
}

void HttpService::addSchema(const std::string& name, nlohmann::json schema) {
  schemas_[name] = std::move(schema);
}

void HttpService::handleUnrouted(const httplib::Request& req, httplib::Response& res) {
  std::string code = "http_error";
  std::string message = "the request could not be served";
  if (res.status == 404) {
    std::string allowed;
    for (const Registered& r : routes_) {
      if (std::regex_match(req.path, r.pattern)) allowed += allowedMethods(allowed, r.route.method);
    }
    if (allowed.empty()) {
      code = "not_found";
      message = "no route " + req.method + " " + req.path;
    } else {
      res.status = 405;
      res.set_header("Allow", allowed);
      code = "method_not_allowed";
      message = req.path + " takes " + allowed;
    }
  } else if (res.status == 413) {
    code = "body_too_large";
    message = "the body is larger than the limit of " + std::to_string(settings_.max_body_bytes) +
              " bytes";
  } else if (res.status == 400 && currentConnection() != nullptr &&
             currentConnection()->bodyOverflow) {
    res.status = 413;  // the chunked body ran past its budget
    res.set_header("Connection", "close");
    code = "body_too_large";
    message = "the body is larger than the limit of " + std::to_string(settings_.max_body_bytes) +
              " bytes";
  } else if (res.status == 400) {
    code = "bad_request";
    message = "the HTTP request is malformed";
  } else if (res.status == 416) {
    // cpp-httplib refuses a Range header it cannot parse before any route sees it.
    code = "bad_range";
    message = "the Range header is not a valid bytes range; send the request without it";
  }
  const int status = res.status;
  sendError(res, HttpError(status, code, message));
  const bool screened = currentConnection() != nullptr && !currentConnection()->label.empty();
  record(screened ? currentConnection()->label : "(unrouted)", req, res, 0.0);
}

bool HttpService::screen(const httplib::Request& req, httplib::Response& res) {
  const Clock::time_point started = Clock::now();
  Connection* conn = currentConnection();
  if (conn != nullptr) conn->inHead = false;
  // cpp-httplib 0.11.4 applies a Range header to every reply, errors and JSON
  // included: a 200 with a cut body, and past the end of a streamed one a
  // Content-Length near 2^64. Routes that serve ranges read the header themselves
  // (requestedByteRange); the rest ignore it (RFC 9110 14.2 allows it) and say so.
  const_cast<httplib::Request&>(req).ranges.clear();
  if (req.method == "HEAD" && !res.has_header("Accept-Ranges"))
    res.set_header("Accept-Ranges", "none");
  const Registered* match = nullptr;
  std::string allowed;
  for (const Registered& r : routes_) {
    if (!segmentsMatch(r.segments, req.path)) continue;
    allowed += allowedMethods(allowed, r.route.method);
    if (r.route.method == req.method || (req.method == "HEAD" && r.route.method == "GET"))
      match = &r;
  }
  const std::string label = match != nullptr ? match->route.path : "(unrouted)";
  if (conn != nullptr) conn->label = label;

  // What framing the body has. cpp-httplib reads a body for these methods only.
  const bool bodyMethod = req.method == "POST" || req.method == "PUT" || req.method == "PATCH" ||
                          req.method == "DELETE";
  const bool hasTransfer = req.has_header("Transfer-Encoding");
  const bool chunked = hasTransfer && iequals(req.get_header_value("Transfer-Encoding"), "chunked");
  const std::size_t lengths = req.get_header_value_count("Content-Length");
  std::optional<std::uint64_t> length;
  bool badLength = false;
  for (std::size_t i = 0; i < lengths; ++i) {
    const auto v = contentLength(req.get_header_value("Content-Length", i));
    badLength |= !v || (length && *length != *v);
    length = v;
  }
  const bool pending = hasTransfer || (length && *length > 0) || badLength;

  auto refuse = [&](const HttpError& e) {
    if (pending && conn != nullptr) {
      conn->close = true;  // its body stays unread: this connection ends with the reply
      res.set_header("Connection", "close");
    }
    if (e.status() == 401) res.set_header("WWW-Authenticate", "Bearer");
    if (e.status() == 405) res.set_header("Allow", allowed);
    sendError(res, e);
    record(label, req, res, std::chrono::duration<double>(Clock::now() - started).count());
    return true;
  };

  if (badLength) {
    return refuse(HttpError(400, "bad_request", "Content-Length must be one non-negative integer"));
  }
  if (hasTransfer && (!chunked || lengths > 0)) {
    return refuse(HttpError(400, "bad_request",
                            "Transfer-Encoding must be chunked, without a Content-Length"));
  }
  if (match == nullptr && allowed.empty()) {
    return refuse(HttpError(404, "not_found", "no route " + req.method + " " + req.path));
  }
  if (match == nullptr) {
    return refuse(HttpError(405, "method_not_allowed", req.path + " takes " + allowed));
  }
  if (match->route.auth) {
    try {
      auth_.check(req);
    } catch (const HttpError& e) {
      return refuse(e);
    }
  }
  if (req.has_header("Content-Encoding") &&
      !iequals(req.get_header_value("Content-Encoding"), "identity")) {
    return refuse(HttpError(415, "unsupported_media_type",
                            "compressed bodies (Content-Encoding) are not accepted"));
  }
  if (length && *length > settings_.max_body_bytes) {
    return refuse(HttpError(413, "body_too_large",
                            "the body is larger than the limit of " +
                                std::to_string(settings_.max_body_bytes) + " bytes"));
  }
  if (!bodyMethod) {
    // cpp-httplib reads no body here; one that came along cannot be skipped.
    if (pending && conn != nullptr) conn->close = true;
    return false;
  }
  if (req.method == "DELETE" && hasTransfer && lengths == 0 && conn != nullptr) {
    conn->close = true;  // cpp-httplib reads a DELETE body by Content-Length only
  }
  if (chunked && conn != nullptr) {
    // Chunk framing on top of the body: a little slack; the route wrapper checks the
    // decoded size against the limit itself.
    conn->bodyBudget = settings_.max_body_bytes + settings_.max_body_bytes / 16 + 65536;
  }
  if (!hasTransfer && lengths == 0 && req.method != "DELETE") {
    // No framing means no body (RFC 9112 6.3); cpp-httplib would read to the end of
    // the connection. The request object is the library's own, not a const one.
    const_cast<httplib::Request&>(req).set_header("Content-Length", "0");
  }
  return false;
}

void HttpService::record(const std::string& label, const httplib::Request& req,
                         const httplib::Response& res, double seconds) {
  const int status = res.status < 0 ? 200 : res.status;
  metrics_.countRequest(label, req.method, status, seconds);
  log_.write("request", {{"method", req.method},
                         {"path", req.path},
                         {"route", label},
                         {"status", status},
                         {"ms", seconds * 1000.0},
                         {"bytes", res.body.size()},
                         {"remote", req.remote_addr}});
}

void HttpService::start() {
  if (thread_.joinable()) return;
  errno = 0;
  if (settings_.port == 0) {
    port_ = server_->bind_to_any_port(settings_.bind);
  } else {
    port_ = server_->bind_to_port(settings_.bind, settings_.port) ? settings_.port : -1;
  }
  if (port_ <= 0) {
    const int error = errno;  // the failed bind's, when the library left it
    throw std::runtime_error(
        "cannot listen on " + settings_.bind + ":" + std::to_string(settings_.port) + ": " +
        (error == EADDRINUSE ? std::string("the address is in use (another service on it?)")
         : error != 0        ? std::string(std::strerror(error))
                             : std::string("the address is unusable")));
  }
  thread_ = std::thread([this] { server_->listen_after_bind(); });
  while (!server_->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void HttpService::stop() {
  if (!thread_.joinable()) return;
  server_->stop();
  thread_.join();
}

nlohmann::json HttpService::openApi() const {
  nlohmann::json paths = nlohmann::json::object();
  for (const Registered& r : routes_) {
    nlohmann::json op = r.route.operation;
    // What the front answers for any route before its handler runs, unless the
    // operation says it already: the bearer check, and a body's size and type.
    nlohmann::json& responses = op["responses"];
    auto common = [&responses](const char* status, const char* what) {
      if (!responses.contains(status)) responses[status] = errorResponse(what);
    };
    if (r.route.auth && auth_.enabled()) {
      op["security"] = nlohmann::json::array({{{"bearer", nlohmann::json::array()}}});
      common("401", "No bearer token (WWW-Authenticate: Bearer).");
      common("403", "Token not accepted.");
    }
    if (r.route.method == "POST" || r.route.method == "PUT" || r.route.method == "PATCH") {
      common("400", "Bad JSON or a bad field, or bad framing.");
      common("413", "Body over the limit (max_body_bytes).");
      common("415", "Not application/json, or a compressed body.");
    }
    // Path parameters from the template, unless the operation declares them.
    if (!op.contains("parameters")) {
      nlohmann::json params = nlohmann::json::array();
      std::size_t i = 0;
      while ((i = r.route.path.find('{', i)) != std::string::npos) {
        const std::size_t close = r.route.path.find('}', i);
        params.push_back({{"name", r.route.path.substr(i + 1, close - i - 1)},
                          {"in", "path"},
                          {"required", true},
                          {"schema", {{"type", "string"}}}});
        i = close;
      }
      if (!params.empty()) op["parameters"] = params;
    }
    std::string method = r.route.method;
    for (char& c : method) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    paths[r.route.path][method] = op;
  }
  nlohmann::json components = {{"schemas", schemas_}};
  components["securitySchemes"] = {{"bearer", {{"type", "http"}, {"scheme", "bearer"}}}};
  return {{"openapi", "3.1.0"},
          {"info",
           {{"title", "mdhd"},
            {"version", "1"},
            {"description",
             "Verification of 5-axis CNC milling programs on multidirectional heightmaps "
             "(service contract version 1)."}}},
          {"servers", nlohmann::json::array({{{"url", "/"}}})},
          {"paths", paths},
          {"components", components}};
}

}  // namespace mdhd::service

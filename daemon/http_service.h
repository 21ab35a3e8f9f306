#pragma once
// The HTTP front of `mdhd serve` on cpp-httplib: routes registered by their
// OpenAPI path template ("/api/v1/jobs/{id}"), each wrapped so that bearer auth,
// JSON errors, one JSON log line and the request metrics apply to every route,
// and the OpenAPI document is assembled from the registrations. Route files
// (routes_jobs.cpp, routes_machines.cpp, routes_ops.cpp, ...) add their routes
// before start(). docs/daemon.md says how to add more.
#include <chrono>
#include <functional>
#include <memory>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "daemon/auth.h"
#include "daemon/json_log.h"
#include "daemon/metrics.h"

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace mdhd::service {

using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

struct HttpSettings {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port
  std::vector<std::string> tokens;
  int threads = 16;
  std::size_t max_body_bytes = 16u << 20;
  // The request line and headers must arrive within this, in all (a client sending
  // one header line every few seconds holds a connection thread no longer), and be
  // at most `max_head_bytes` long.
  std::chrono::milliseconds head_timeout{10000};
  std::size_t max_head_bytes = 64u << 10;
};

struct Route {
  std::string method;  // GET, POST, PUT, DELETE
  // OpenAPI path template; each {param} matches one path segment and is
  // req.matches[1], [2], ... in order. Also the route's label in logs and metrics.
  std::string path;
  // The OpenAPI operation object (summary, parameters, requestBody, responses).
  nlohmann::json operation = nlohmann::json::object();
  bool auth = true;  // false: open even when tokens are configured (/healthz)
};

class HttpService {
 public:
  HttpService(HttpSettings settings, JsonLog& log, Metrics& metrics);
  ~HttpService();
  HttpService(const HttpService&) = delete;
  HttpService& operator=(const HttpService&) = delete;

  // Registers a route. Handlers throw HttpError for error replies.
  void route(Route route, Handler handler);
  // A named schema for "#/components/schemas/<name>" in the OpenAPI document.
  void addSchema(const std::string& name, nlohmann::json schema);

  // Binds and serves on a thread of its own. Throws std::runtime_error when the
  // address cannot be bound.
  void start();
  // Stops accepting, closes connections and joins the thread. Idempotent.
  void stop();
  int port() const { return port_; }
  const std::string& bind() const { return settings_.bind; }

  // The OpenAPI 3.1 document of every registered route.
  nlohmann::json openApi() const;

 private:
  void handleUnrouted(const httplib::Request& req, httplib::Response& res);
  // Pre-routing, after the headers and before any body is read: framing
  // (Content-Length, Transfer-Encoding, Content-Encoding), 404/405, the bearer
  // check and the body limit. True when it replied (the body is then never read).
  bool screen(const httplib::Request& req, httplib::Response& res);
  void record(const std::string& label, const httplib::Request& req, const httplib::Response& res,
              double seconds);

  HttpSettings settings_;
  JsonLog& log_;
  Metrics& metrics_;
  Auth auth_;
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
  int port_ = 0;
  struct Registered {
    Route route;
    std::regex pattern;
    std::vector<std::string> segments;  // of the template; "{...}" matches any one
  };
  std::vector<Registered> routes_;
  nlohmann::json schemas_ = nlohmann::json::object();
};

// Path parameter i (1-based) of a route.
std::string pathParam(const httplib::Request& req, std::size_t i);

// The regex a path template becomes ("{x}" -> one segment).
std::string pathPattern(const std::string& path);

}  // namespace mdhd::service

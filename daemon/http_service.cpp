#include "daemon/http_service.h"

#include <httplib.h>

#include <chrono>
#include <stdexcept>

#include "daemon/http_errors.h"

namespace mdhd::service {
namespace {

using Clock = std::chrono::steady_clock;

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
      server_(std::make_unique<httplib::Server>()) {
  const int threads = settings_.threads;
  server_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server_->set_tcp_nodelay(true);  // else Nagle adds tens of ms to keep-alive replies
  server_->set_payload_max_length(settings_.max_body_bytes);
  server_->set_read_timeout(10, 0);
  server_->set_write_timeout(10, 0);
  server_->set_keep_alive_timeout(5);
  server_->set_keep_alive_max_count(1000);
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
  routes_.push_back({std::move(route), std::regex(pattern)});
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
      if (std::regex_match(req.path, r.pattern))
        allowed += (allowed.empty() ? "" : ", ") + r.route.method;
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
  } else if (res.status == 400) {
    code = "bad_request";
    message = "the HTTP request is malformed";
  }
  const int status = res.status;
  sendError(res, HttpError(status, code, message));
  record("(unrouted)", req, res, 0.0);
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
  if (settings_.port == 0) {
    port_ = server_->bind_to_any_port(settings_.bind);
  } else {
    port_ = server_->bind_to_port(settings_.bind, settings_.port) ? settings_.port : -1;
  }
  if (port_ <= 0) {
    throw std::runtime_error("cannot listen on " + settings_.bind + ":" +
                             std::to_string(settings_.port));
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
    if (r.route.auth && auth_.enabled())
      op["security"] = nlohmann::json::array({{{"bearer", nlohmann::json::array()}}});
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

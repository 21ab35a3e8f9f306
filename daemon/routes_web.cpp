#include "daemon/routes_web.h"

#include <httplib.h>

#include "daemon/http_errors.h"
#include "daemon/openapi_parts.h"
#include "daemon/web_assets.h"

namespace mdhd::service {
namespace {

// The page loads nothing from elsewhere and may not be framed (clickjacking).
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; img-src 'self' data: blob:; style-src 'self'; script-src 'self'; "
    "connect-src 'self'; object-src 'none'; base-uri 'none'; frame-ancestors 'none'";

void serveAsset(const httplib::Request& req, httplib::Response& res, std::string_view name) {
  const WebAsset* asset = findWebAsset(name);
  if (asset == nullptr) {
    throw HttpError(404, "not_found", "the UI has no file " + std::string(name));
  }
  res.set_header("Content-Security-Policy", kContentSecurityPolicy);
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("Referrer-Policy", "no-referrer");
  // Revalidate every time: a new mdhd version must not run with an old cached script.
  res.set_header("Cache-Control", "no-cache");
  res.set_header("ETag", asset->etag);
  if (req.get_header_value("If-None-Match") == asset->etag) {
    res.status = 304;
    return;
  }
  res.status = 200;
  res.set_content(std::string(asset->body), asset->mime);
}

nlohmann::json fileResponse(const std::string& description, const std::string& media) {
  return {{"description", description}, {"content", {{media, {{"schema", {{"type", "string"}}}}}}}};
}

}  // namespace

void addWebRoutes(HttpService& http) {
  http.route({"GET",
              "/",
              {{"summary", "The browser UI: jobs, their reports and meshes, live shadows"},
               {"tags", {"ui"}},
               {"responses",
                {{"200", fileResponse("The page.", "text/html")},
                 {"304", {{"description", "Unchanged since the ETag sent."}}}}}},
              false},
             [](const httplib::Request& req, httplib::Response& res) {
               serveAsset(req, res, "index.html");
             });
  http.route({"GET",
              "/ui/{name}",
              {{"summary", "A script, style sheet or image of the browser UI"},
               {"tags", {"ui"}},
               {"parameters",
                {{{"name", "name"},
                  {"in", "path"},
                  {"required", true},
                  {"schema", {{"type", "string"}}}}}},
               {"responses",
                {{"200", fileResponse("The file.", "text/javascript")},
                 {"304", {{"description", "Unchanged since the ETag sent."}}},
                 {"404", errorResponse("The UI has no such file.")}}}},
              false},
             [](const httplib::Request& req, httplib::Response& res) {
               serveAsset(req, res, pathParam(req, 1));
             });
}

}  // namespace mdhd::service

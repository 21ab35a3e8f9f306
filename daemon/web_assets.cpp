#include "daemon/web_assets.h"

#include <cstdint>
#include <cstdio>
#include <vector>

namespace mdhd::service {
namespace {

bool endsWith(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

// FNV-1a, 64 bits: a validator for caches, not a security measure.
std::string etagOf(std::string_view body) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : body) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  char text[24];
  std::snprintf(text, sizeof text, "\"%016llx\"", static_cast<unsigned long long>(h));
  return text;
}

const std::vector<WebAsset>& assets() {
  static const std::vector<WebAsset> all = [] {
    std::vector<WebAsset> list;
    for (const EmbeddedFile& f : embeddedWebFiles())
      list.push_back({f.name, f.body, mimeTypeFor(f.name), etagOf(f.body)});
    return list;
  }();
  return all;
}

}  // namespace

std::string mimeTypeFor(std::string_view name) {
  if (endsWith(name, ".html")) return "text/html; charset=utf-8";
  if (endsWith(name, ".js") || endsWith(name, ".mjs")) return "text/javascript; charset=utf-8";
  if (endsWith(name, ".css")) return "text/css; charset=utf-8";
  if (endsWith(name, ".svg")) return "image/svg+xml";
  if (endsWith(name, ".json")) return "application/json";
  return "application/octet-stream";
}

const WebAsset* findWebAsset(std::string_view name) {
  for (const WebAsset& a : assets()) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

}  // namespace mdhd::service

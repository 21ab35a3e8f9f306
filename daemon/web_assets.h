#pragma once
// The browser UI's files (web/), compiled into the executable by
// cmake/embed_web.cmake and served by routes_web.cpp.
#include <span>
#include <string>
#include <string_view>

namespace mdhd::service {

struct EmbeddedFile {
  std::string_view name;  // base name in web/, e.g. "app.js"
  std::string_view body;
};

// Every embedded file (generated: web_files.cpp in the build tree).
std::span<const EmbeddedFile> embeddedWebFiles();

struct WebAsset {
  std::string_view name;
  std::string_view body;
  std::string mime;  // Content-Type
  std::string etag;  // strong validator of the body, quoted
};

// The asset called `name`, or nullptr. Names are matched exactly: no paths.
const WebAsset* findWebAsset(std::string_view name);

// Content-Type for a file name by its extension (application/octet-stream if unknown).
std::string mimeTypeFor(std::string_view name);

}  // namespace mdhd::service

#pragma once
// The browser UI: GET / (the page) and GET /ui/{name} (its scripts and styles),
// served from the files compiled into the executable (web_assets.h). Open without
// a token: the page holds no data; its API calls carry the user's token.
#include "daemon/http_service.h"

namespace mdhd::service {

void addWebRoutes(HttpService& http);

}  // namespace mdhd::service

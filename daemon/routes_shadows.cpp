#include "daemon/routes_shadows.h"

#include <httplib.h>

#include "daemon/check_runner.h"
#include "daemon/http_errors.h"
#include "daemon/number_text.h"
#include "daemon/openapi_parts.h"
#include "protocol/machine_json.h"

namespace mdhd::service {
namespace {

using shadow::ShadowSession;

constexpr const char* kShadows = "/api/v1/shadows";
// How long a stream waits for events before it checks its client and the service.
constexpr auto kStreamWait = std::chrono::milliseconds(250);
// A comment line this often keeps proxies from closing a quiet stream.
constexpr auto kHeartbeat = std::chrono::seconds(10);

std::shared_ptr<ShadowSession> findShadow(shadow::ShadowRegistry& shadows,
                                          const httplib::Request& req) {
  const std::string id = pathParam(req, 1);
  auto s = shadows.find(id);
  if (!s) throw HttpError(404, "not_found", "no shadow " + id.substr(0, 64));
  return s;
}

HttpError badField(const std::string& field, const std::string& message) {
  return HttpError(400, "bad_field", field + ": " + message, {{"field", field}});
}

std::unique_ptr<ShadowSession> makeSession(const nlohmann::json& body, JobStore& store,
                                           const ServiceConfig& config) {
  if (!body.is_object()) throw badField("(document)", "a shadow request must be a JSON object");
  const auto program = body.find("program");
  if (program != body.end() && program->is_string() &&
      program->get_ref<const std::string&>().size() > config.max_program_bytes) {
    throw HttpError(413, "program_too_large",
                    "the program is longer than the limit of " +
                        std::to_string(config.max_program_bytes) + " bytes",
                    {{"field", "program"}});
  }
  const shadow::MachineLookup lookup = [&store](const std::string& name) {
    std::optional<kin::Machine> out;
    if (!isMachineName(name)) return out;
    if (const auto m = store.machine(name))
      out = protocol::machineFromJson(nlohmann::json::parse(m->machine), "machine");
    return out;
  };
  try {
    shadow::ShadowSpec spec = shadow::shadowSpecFromJson(body, lookup);
    cli::requireStockFits(spec.job);
    return std::make_unique<ShadowSession>(shadow::ShadowRegistry::newId(), std::move(spec));
  } catch (const protocol::FieldError& e) {
    throw badField(e.field(), e.message());
  } catch (const gcode::GcodeError& e) {
    nlohmann::json extra = {{"line", e.line()}, {"column", e.column()}};
    if (!e.pos().file.empty()) extra["file"] = e.pos().file;
    throw HttpError(422, "program_error",
                    "program line " + std::to_string(e.line()) + ", column " +
                        std::to_string(e.column()) + ": " + e.what(),
                    std::move(extra));
  } catch (const kin::KinematicsError& e) {
    throw badField("machine", e.what());
  } catch (const std::invalid_argument& e) {
    throw badField("(job)", e.what());
  }
}

void postShadow(const httplib::Request& req, httplib::Response& res,
                shadow::ShadowRegistry& shadows, JobStore& store, const ServiceConfig& config) {
  std::unique_ptr<ShadowSession> session = makeSession(parseJsonBody(req), store, config);
  const std::string id = session->id();
  if (!shadows.add(std::move(session))) {
    res.set_header("Retry-After", "5");
    throw HttpError(
        429, "too_many_shadows",
        "at most " + std::to_string(kMaxShadows) + " shadows run at once; stop one (DELETE) first");
  }
  res.set_header("Location", std::string(kShadows) + "/" + id);
  sendJson(res, 201, {{"id", id}, {"state", "connecting"}});
}

std::string sseText(const shadow::ShadowEvent& e) {
  return "id: " + std::to_string(e.id) + "\nevent: " + e.type + "\ndata: " + e.data + "\n\n";
}

// Streams the shadow's events from `after` on until the shadow stops, the
// client goes away or the service closes.
void streamEvents(const httplib::Request& req, httplib::Response& res,
                  shadow::ShadowRegistry& shadows) {
  std::shared_ptr<ShadowSession> s = findShadow(shadows, req);
  // A reconnecting EventSource sends the last id it saw; a new stream starts
  // with the state now, then what happens from here on.
  std::uint64_t after = s->events().lastId();
  std::string first = "retry: 1000\n";
  if (req.has_header("Last-Event-ID")) {
    // Digits only: stoull read "1e3" as 1 (a resume from event 2) and "-5" as a huge id.
    const std::optional<std::uint64_t> id =
        decimalDigits(req.get_header_value("Last-Event-ID"), 19);
    if (!id) throw HttpError(400, "bad_header", "Last-Event-ID: not an event id (digits only)");
    after = std::min(*id, after);
  } else {
    first += "event: state\ndata: " +
             nlohmann::json({{"state", shadow::shadowStateName(s->state())}}).dump() + "\n\n";
  }
  if (!shadows.openStream()) {
    res.set_header("Retry-After", "5");
    throw HttpError(503, "too_many_streams", "too many event streams are open; try again later");
  }
  res.set_header("Cache-Control", "no-cache");
  res.set_header("X-Accel-Buffering", "no");
  auto heartbeat = std::make_shared<std::chrono::steady_clock::time_point>(
      std::chrono::steady_clock::now() + kHeartbeat);
  res.set_chunked_content_provider(
      "text/event-stream",
      [s, &shadows, after, first, heartbeat](std::size_t, httplib::DataSink& sink) mutable {
        if (!first.empty()) {
          if (!sink.write(first.data(), first.size())) return false;
          first.clear();
        }
        bool missed = false;
        const auto events = s->events().since(after, kStreamWait, &missed);
        std::string text;
        if (missed) text += ": some events were dropped from the buffer\n\n";
        for (const shadow::ShadowEvent& e : events) {
          text += sseText(e);
          after = e.id;
        }
        const auto now = std::chrono::steady_clock::now();
        if (text.empty() && now >= *heartbeat) text = ":\n\n";
        if (!text.empty()) {
          *heartbeat = now + kHeartbeat;
          if (!sink.write(text.data(), text.size())) return false;
        }
        if ((s->events().closed() && after >= s->events().lastId()) || shadows.closing()) {
          sink.done();
        }
        return true;
      },
      [&shadows](bool) { shadows.closeStream(); });
}

void stopOrDelete(const httplib::Request& req, httplib::Response& res,
                  shadow::ShadowRegistry& shadows) {
  std::shared_ptr<ShadowSession> s = findShadow(shadows, req);
  if (s->state() == shadow::ShadowState::kStopped) {
    shadows.remove(s->id());
    res.status = 204;
    return;
  }
  s->stop();
  sendJson(res, 200, s->status());
}

nlohmann::json idParameter() {
  return nlohmann::json::array(
      {{{"name", "id"}, {"in", "path"}, {"required", true}, {"schema", {{"type", "string"}}}}});
}

nlohmann::json shadowStateSchema() {
  return {{"type", "object"},
          {"required", {"id", "state", "joints", "tool_pose", "samples", "alarms", "report"}},
          {"properties",
           {{"id", {{"type", "string"}}},
            {"state", {{"enum", {"connecting", "live", "stale", "stopped"}}}},
            {"joints", {{"type", "object"}, {"additionalProperties", {{"type", "number"}}}}},
            {"tool_pose", {{"type", "object"}}},
            {"samples", {{"type", "integer"}}},
            {"alarms", {{"type", "array"}, {"items", {{"type", "object"}}}}},
            {"report", schemaRef("Report")}}}};
}

}  // namespace

void addShadowRoutes(HttpService& http, shadow::ShadowRegistry& shadows, JobStore& store,
                     const ServiceConfig& config) {
  http.addSchema("ShadowState", shadowStateSchema());
  const nlohmann::json tags = nlohmann::json::array({"shadows"});
  http.route({"POST",
              kShadows,
              {{"summary", "Start shadowing a machine over Modbus TCP"},
               {"tags", tags},
               {"description",
                "Body: the job fields of the cell (machine or a registered machine's name, tools, "
                "stock, fixtures, work_offsets, options, optionally program) and a modbus block "
                "(docs/modbus.md). A shadow is live state, not a durable job: a daemon restart "
                "ends it."},
               {"requestBody",
                {{"required", true},
                 {"content", {{"application/json", {{"schema", {{"type", "object"}}}}}}}}},
               {"responses",
                {{"201", jsonResponse("Started; Location names it.", {{"type", "object"}})},
                 {"400", errorResponse("Bad JSON or field.")},
                 {"413", errorResponse("Program too long.")},
                 {"422", errorResponse("The program does not interpret.")},
                 {"429", errorResponse("Too many shadows.")}}}}},
             [&](const httplib::Request& req, httplib::Response& res) {
               postShadow(req, res, shadows, store, config);
             });
  http.route({"GET",
              kShadows,
              {{"summary", "The shadows: id, state, samples, host and port of each"},
               {"tags", tags},
               {"description",
                "Running and stopped (not yet deleted) shadows, by id: for a client that lost "
                "an id. The full state of one is GET /api/v1/shadows/{id}."},
               {"responses",
                {{"200", jsonResponse("{\"shadows\": [{\"id\", \"state\", \"samples\", "
                                      "\"host\", \"port\"}, ...]}",
                                      {{"type", "object"}})}}}}},
             [&shadows](const httplib::Request&, httplib::Response& res) {
               nlohmann::json list = nlohmann::json::array();
               for (const auto& s : shadows.all()) list.push_back(s->summary());
               sendJson(res, 200, {{"shadows", std::move(list)}});
             });
  http.route({"GET",
              std::string(kShadows) + "/{id}",
              {{"summary", "A shadow's state, pose, alarms and live report"},
               {"tags", tags},
               {"parameters", idParameter()},
               {"responses",
                {{"200", jsonResponse("The state.", schemaRef("ShadowState"))},
                 {"404", errorResponse("No such shadow.")}}}}},
             [&shadows](const httplib::Request& req, httplib::Response& res) {
               sendJson(res, 200, findShadow(shadows, req)->status());
             });
  http.route({"GET",
              std::string(kShadows) + "/{id}/events",
              {{"summary", "Server-Sent Events: pose, alarm, alarm_update, state"},
               {"tags", tags},
               {"description",
                "event: state, pose, alarm or alarm_update; data: one line of JSON. A collision "
                "alarm is sent the moment the contact is found, with depth_measured false and "
                "a first bound of its depth; an alarm_update with the same alarm id follows "
                "with the measured depth (depth_measured true). docs/shadow.md."},
               {"parameters", idParameter()},
               {"responses",
                {{"200",
                  {{"description", "An event stream."},
                   {"content", {{"text/event-stream", {{"schema", {{"type", "string"}}}}}}}}},
                 {"404", errorResponse("No such shadow.")},
                 {"503", errorResponse("Too many open streams.")}}}}},
             [&shadows](const httplib::Request& req, httplib::Response& res) {
               streamEvents(req, res, shadows);
             });
  http.route({"GET",
              std::string(kShadows) + "/{id}/mesh",
              {{"summary", "The live stock so far, binary STL"},
               {"tags", tags},
               {"parameters", idParameter()},
               {"responses",
                {{"200",
                  {{"description", "Binary STL (mm, workpiece frame)."},
                   {"content",
                    {{"model/stl", {{"schema", {{"type", "string"}, {"format", "binary"}}}}}}}}},
                 {"404", errorResponse("No such shadow.")},
                 {"409", errorResponse("The mesh is over `max_mesh_mb` (`mesh_too_large`).")}}}}},
             [&shadows, &config](const httplib::Request& req, httplib::Response& res) {
               // Built in memory: capped like a job's mesh file, or a fine live stock
               // could take the service's memory with it.
               std::string stl;
               const cli::StlOutcome outcome =
                   findShadow(shadows, req)->stockStl(stl, config.max_mesh_mb << 20);
               if (outcome.failure == cli::StlOutcome::Failure::kTooLarge) {
                 throw HttpError(409, "mesh_too_large", outcome.error);
               }
               res.set_content(stl, "model/stl");
             });
  http.route({"DELETE",
              std::string(kShadows) + "/{id}",
              {{"summary", "Stops a shadow; deletes a stopped one"},
               {"tags", tags},
               {"parameters", idParameter()},
               {"responses",
                {{"200", jsonResponse("Stopped: its last state.", schemaRef("ShadowState"))},
                 {"204", {{"description", "Deleted."}}},
                 {"404", errorResponse("No such shadow.")}}}}},
             [&shadows](const httplib::Request& req, httplib::Response& res) {
               stopOrDelete(req, res, shadows);
             });
}

}  // namespace mdhd::service

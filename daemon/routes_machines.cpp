#include "daemon/routes_machines.h"

#include <httplib.h>

#include "daemon/http_errors.h"
#include "daemon/openapi_parts.h"
#include "protocol/machine_json.h"
#include "sim/kinematics/presets.h"

namespace mdhd::service {
namespace {

constexpr const char* kMachines = "/api/v1/machines";

std::string machineName(const httplib::Request& req) {
  const std::string name = pathParam(req, 1);
  if (!isMachineName(name)) {
    throw HttpError(400, "bad_name",
                    "a machine name is 1 to 64 letters, digits, '.', '_' or '-', starting with "
                    "a letter or digit",
                    {{"field", "name"}});
  }
  return name;
}

MachineRecord findMachine(JobStore& store, const httplib::Request& req) {
  const std::string name = pathParam(req, 1);
  std::optional<MachineRecord> m;
  if (isMachineName(name)) m = store.machine(name);
  if (!m) throw HttpError(404, "not_found", "no machine " + name.substr(0, 64));
  return *m;
}

nlohmann::json listEntry(const MachineRecord& m) {
  const nlohmann::json doc = nlohmann::json::parse(m.machine);
  nlohmann::json joints = nlohmann::json::array();
  for (const auto& j : doc["joints"]) joints.push_back(j["name"]);
  nlohmann::json out = {{"name", m.name}, {"joints", joints}, {"updated_at", m.updated_at}};
  if (doc.contains("name")) out["description"] = doc["name"];
  return out;
}

}  // namespace

void registerExampleMachines(JobStore& store) {
  constexpr const char* kFlag = "example_machines_registered";
  if (store.flag(kFlag)) return;  // once: a machine the user deleted stays deleted
  namespace p = kin::presets;
  const std::pair<const char*, kin::Machine> presets[] = {
      {"3axis-mill", p::threeAxisMill()}, {"ac-trunnion", p::acTrunnion()},
      {"bc-trunnion", p::bcTrunnion()},   {"bc-head-table", p::bcHeadTable()},
      {"ab-head-head", p::abHeadHead()},  {"bc-head-head", p::bcHeadHead()},
      {"nutating-b45", p::nutatingB45()}};
  for (const auto& [name, machine] : presets) {
    if (!store.machine(name)) store.putMachine(name, protocol::machineToJson(machine).dump());
  }
  store.setFlag(kFlag);
}

void addMachineRoutes(HttpService& http, JobStore& store) {
  const nlohmann::json notFound = errorResponse("No such machine.");
  http.route({"GET",
              kMachines,
              {{"summary", "Registered machines"},
               {"tags", {"machines"}},
               {"responses",
                {{"200", jsonResponse("Every machine by name, with its joints.",
                                      {{"type", "object"},
                                       {"properties", {{"machines", {{"type", "array"}}}}}})}}}}},
             [&store](const httplib::Request&, httplib::Response& res) {
               nlohmann::json list = nlohmann::json::array();
               for (const MachineRecord& m : store.machines()) list.push_back(listEntry(m));
               sendJson(res, 200, {{"machines", list}});
             });
  http.route({"PUT",
              std::string(kMachines) + "/{name}",
              {{"summary", "Register or replace a machine"},
               {"tags", {"machines"}},
               {"requestBody",
                {{"required", true},
                 {"content", {{"application/json", {{"schema", schemaRef("Job_machine")}}}}}}},
               {"responses",
                {{"200", jsonResponse("Replaced.", schemaRef("Job_machine"))},
                 {"201", jsonResponse("Created.", schemaRef("Job_machine"))},
                 {"400", errorResponse("Bad name, JSON or field (`field` names it).")}}}}},
             [&store](const httplib::Request& req, httplib::Response& res) {
               const std::string name = machineName(req);
               const nlohmann::json doc = parseJsonBody(req);
               try {
                 protocol::machineFromJson(doc, "machine");
               } catch (const protocol::FieldError& e) {
                 throw HttpError(400, "bad_field", e.what(), {{"field", e.field()}});
               }
               const bool created = store.putMachine(name, doc.dump());
               if (created) res.set_header("Location", std::string(kMachines) + "/" + name);
               sendJson(res, created ? 201 : 200, doc);
             });
  http.route({"GET",
              std::string(kMachines) + "/{name}",
              {{"summary", "A registered machine"},
               {"tags", {"machines"}},
               {"responses",
                {{"200", jsonResponse("The machine as registered.", schemaRef("Job_machine"))},
                 {"404", notFound}}}}},
             [&store](const httplib::Request& req, httplib::Response& res) {
               sendJsonText(res, 200, findMachine(store, req).machine);
             });
  http.route({"DELETE",
              std::string(kMachines) + "/{name}",
              {{"summary", "Remove a machine (accepted jobs keep their copy)"},
               {"tags", {"machines"}},
               {"responses", {{"204", {{"description", "Removed."}}}, {"404", notFound}}}}},
             [&store](const httplib::Request& req, httplib::Response& res) {
               const MachineRecord m = findMachine(store, req);
               store.deleteMachine(m.name);
               res.status = 204;
             });
}

}  // namespace mdhd::service

#include "daemon/routes_jobs.h"

#include <httplib.h>

#include <fstream>

#include "daemon/http_errors.h"
#include "daemon/openapi_parts.h"
#include "daemon/service_job.h"

namespace mdhd::service {
namespace {

constexpr const char* kJobs = "/api/v1/jobs";

JobRecord findJob(JobStore& store, const httplib::Request& req, bool withJobText = false) {
  const std::string id = pathParam(req, 1);
  std::optional<JobRecord> record;
  if (isJobId(id)) record = store.job(id, withJobText);
  if (!record)
    throw HttpError(404, "not_found", "no job " + id.substr(0, 64), {{"id", id.substr(0, 64)}});
  return *record;
}

double progressOf(const JobRecord& r, const WorkerPool& pool) {
  if (r.status == "done" || r.status == "failed") return 1.0;
  if (r.status == "running") return pool.progress(r.id).value_or(0.0);
  return 0.0;
}

// The report's verdict in a line: what a list of jobs needs to show which are safe.
nlohmann::json verdictOf(const std::string& reportText) {
  const nlohmann::json report = nlohmann::json::parse(reportText, nullptr, false);
  if (!report.is_object() || !report.contains("status")) return nullptr;
  nlohmann::json v = {{"status", report["status"]}};
  const auto collisions = report.find("collisions");
  v["collisions"] = collisions != report.end() && collisions->is_array() ? collisions->size() : 0;
  return v;
}

nlohmann::json summary(const JobRecord& r, const WorkerPool& pool) {
  nlohmann::json j = {{"id", r.id},
                      {"status", r.status},
                      {"progress", progressOf(r, pool)},
                      {"created_at", r.created_at},
                      {"attempts", r.attempts},
                      {"interrupted", r.interrupted}};
  if (!r.machine_name.empty()) j["machine"] = r.machine_name;
  if (!r.started_at.empty()) j["started_at"] = r.started_at;
  if (!r.finished_at.empty()) j["finished_at"] = r.finished_at;
  if (r.mesh) j["mesh"] = std::string(kJobs) + "/" + r.id + "/mesh";
  if (r.report) j["verdict"] = verdictOf(*r.report);
  if (!r.mesh_error.empty()) j["mesh_error"] = nlohmann::json::parse(r.mesh_error, nullptr, false);
  return j;
}

// The status document with the stored report spliced in as it is (no re-parse).
std::string statusText(const JobRecord& r, const WorkerPool& pool) {
  std::string text = summary(r, pool).dump();
  if (r.report) {
    text.pop_back();
    text += ",\"report\":" + *r.report + "}";
  }
  return text;
}

void postJob(const httplib::Request& req, httplib::Response& res, JobStore& store, WorkerPool& pool,
             const ServiceConfig& config) {
  AcceptedJob accepted =
      acceptJob(parseJsonBody(req), config.max_program_bytes,
                [&store](const std::string& name) -> std::optional<nlohmann::json> {
                  const auto m = store.machine(name);
                  if (!m) return std::nullopt;
                  return nlohmann::json::parse(m->machine);
                });
  const std::string id = newJobId();
  const std::string text = accepted.doc.dump();
  switch (pool.submit(id, [&] { store.insertJob(id, text, accepted.machine_name); })) {
    case WorkerPool::Submitted::kQueued:
      break;
    case WorkerPool::Submitted::kQueueFull:
      res.set_header("Retry-After", "5");
      throw HttpError(429, "queue_full",
                      "the job queue is full (" + std::to_string(config.queue_limit) +
                          " waiting); try again later");
    case WorkerPool::Submitted::kStopping:
      throw HttpError(503, "unavailable", "the service is shutting down");
  }
  res.set_header("Location", std::string(kJobs) + "/" + id);
  sendJson(res, 202, {{"id", id}, {"status", "queued"}});
}

void deleteJob(const httplib::Request& req, httplib::Response& res, JobStore& store,
               WorkerPool& pool) {
  const JobRecord r = findJob(store, req);
  if (r.status == "queued" || r.status == "running") {
    const auto result = pool.cancel(r.id, std::chrono::seconds(5));
    if (result == WorkerPool::Cancelled::kNotActive) {
      // In no worker's hands: the pool is stopping, or the job finished since it was
      // read above. Settle it here only in the first case: a finished job keeps its report.
      store.cancelUnfinished(r.id);
    }
    const JobRecord now = *store.job(r.id);
    sendJson(res, now.status == "cancelled" || now.status != "running" ? 200 : 202,
             {{"id", r.id}, {"status", now.status}});
    return;
  }
  store.deleteJob(r.id);
  res.status = 204;
}

void sendMesh(const httplib::Request& req, httplib::Response& res, JobStore& store) {
  const JobRecord r = findJob(store, req);
  if (!r.mesh && !r.mesh_error.empty()) {
    // Done, but the mesh was not written: over --max-mesh-mb, or the write failed.
    const nlohmann::json why = nlohmann::json::parse(r.mesh_error, nullptr, false);
    const bool known = why.is_object() && why.contains("code") && why.contains("message");
    throw HttpError(409, known ? why["code"].get<std::string>() : "no_mesh",
                    known ? why["message"].get<std::string>() : "the job's mesh was not written",
                    {{"status", r.status}});
  }
  if (!r.mesh) {
    throw HttpError(409, "no_mesh",
                    r.status == "done" ? "the job's mesh could not be written"
                                       : "the job has no mesh (status " + r.status + ")",
                    {{"status", r.status}});
  }
  const std::filesystem::path path = store.meshPath(r.id);
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  auto file = std::make_shared<std::ifstream>(path, std::ios::binary);
  if (ec || !*file) throw HttpError(409, "no_mesh", "the job's mesh is gone");
  // One byte range (a resumed download) is served as 206; the library's own range
  // handling is off (HttpService::screen), it cut JSON replies and overflowed here.
  res.headers.erase("Accept-Ranges");
  res.set_header("Accept-Ranges", "bytes");
  const std::optional<ByteRange> range = requestedByteRange(req, res, size);
  const std::uintmax_t first = range ? range->first : 0;
  const std::uintmax_t bytes = range ? range->last - range->first + 1 : size;
  res.status = range ? 206 : 200;
  if (range) {
    res.set_header("Content-Range", "bytes " + std::to_string(range->first) + "-" +
                                        std::to_string(range->last) + "/" + std::to_string(size));
  }
  res.set_header("Content-Disposition", "attachment; filename=\"" + r.id + ".stl\"");
  res.set_content_provider(
      static_cast<std::size_t>(bytes), "model/stl",
      [file, first](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        char buf[1 << 16];
        file->seekg(static_cast<std::streamoff>(first + offset));
        file->read(buf, static_cast<std::streamsize>(std::min(length, sizeof buf)));
        const std::streamsize n = file->gcount();
        return n > 0 && sink.write(buf, static_cast<std::size_t>(n));
      });
}

nlohmann::json jobStatusSchema() {
  return {{"type", "object"},
          {"required", {"id", "status", "progress"}},
          {"properties",
           {{"id", {{"type", "string"}, {"pattern", "^[0-9a-f]{32}$"}}},
            {"status", {{"enum", {"queued", "running", "done", "failed", "cancelled"}}}},
            {"progress", {{"type", "number"}, {"minimum", 0}, {"maximum", 1}}},
            {"machine", {{"type", "string"}, {"description", "The registered machine it named."}}},
            {"created_at", {{"type", "string"}, {"format", "date-time"}}},
            {"started_at", {{"type", "string"}, {"format", "date-time"}}},
            {"finished_at", {{"type", "string"}, {"format", "date-time"}}},
            {"attempts", {{"type", "integer"}, {"description", "Times a worker started it."}}},
            {"interrupted",
             {{"type", "integer"},
              {"description", "Times the service died while it ran (it then runs again)."}}},
            {"mesh", {{"type", "string"}, {"description", "Where the final stock is."}}},
            {"mesh_error",
             {{"type", "object"},
              {"description",
               "Why a done job has no mesh: `mesh_too_large` (over the service's "
               "max_mesh_mb) or `mesh_write_failed` (e.g. disk full)."},
              {"properties",
               {{"code", {{"enum", {"mesh_too_large", "mesh_write_failed"}}}},
                {"message", {{"type", "string"}}}}}}},
            {"verdict",
             {{"type", "object"},
              {"description",
               "When finished: the report's status and its number of collisions, also in "
               "the listing (which carries no reports)."},
              {"properties",
               {{"status", {{"enum", {"clean", "collisions", "error"}}}},
                {"collisions", {{"type", "integer"}, {"minimum", 0}}}}}}},
            {"report", schemaRef("Report")}}}};
}

}  // namespace

void addJobRoutes(HttpService& http, JobStore& store, WorkerPool& pool,
                  const ServiceConfig& config) {
  http.addSchema("JobStatus", jobStatusSchema());
  const nlohmann::json notFound = errorResponse("No such job.");
  http.route(
      {"POST",
       kJobs,
       {{"summary", "Submit a job"},
        {"tags", {"jobs"}},
        {"description",
         "A job document (job-format.md); `machine` may name a registered machine. The "
         "program is interpreted before the job is accepted."},
        {"requestBody",
         {{"required", true}, {"content", {{"application/json", {{"schema", schemaRef("Job")}}}}}}},
        {"responses",
         {{"202",
           jsonResponse("Accepted and committed; Location names it.",
                        {{"type", "object"},
                         {"properties",
                          {{"id", {{"type", "string"}}}, {"status", {{"const", "queued"}}}}}})},
          {"400", errorResponse("Bad JSON or a bad field (`field` names it).")},
          {"401", errorResponse("No bearer token.")},
          {"403", errorResponse("Token not accepted.")},
          {"413", errorResponse("Body or program over the limit.")},
          {"415", errorResponse("Not application/json.")},
          {"422", errorResponse("The program does not interpret (`line`, `column`, `block`).")},
          {"429", errorResponse("The queue is full (Retry-After).")},
          {"503", errorResponse("Shutting down.")}}}}},
      [&](const httplib::Request& req, httplib::Response& res) {
        postJob(req, res, store, pool, config);
      });
  http.route(
      {"GET",
       kJobs,
       {{"summary", "Recent jobs, newest first, paged"},
        {"tags", {"jobs"}},
        {"parameters",
         {{{"name", "limit"},
           {"in", "query"},
           {"schema", {{"type", "integer"}, {"minimum", 1}, {"maximum", 100}, {"default", 20}}}},
          {{"name", "cursor"},
           {"in", "query"},
           {"description", "`next_cursor` of the previous page."},
           {"schema", {{"type", "string"}}}}}},
        {"responses",
         {{"200", jsonResponse("A page of jobs (without reports).",
                               {{"type", "object"},
                                {"properties",
                                 {{"jobs", {{"type", "array"}, {"items", schemaRef("JobStatus")}}},
                                  {"next_cursor", {{"type", {"string", "null"}}}}}}})},
          {"400", errorResponse("Bad, repeated or unknown query parameter (`parameter` "
                                "names it).")}}}}},
      [&](const httplib::Request& req, httplib::Response& res) {
        checkQueryParameters(req, {"limit", "cursor"});
        const int limit = static_cast<int>(queryInteger(req, "limit", 20, 1, 100));
        const std::int64_t cursor = queryInteger(req, "cursor", 0, 1, INT64_MAX);
        const std::vector<JobRecord> page = store.jobs(limit + 1, cursor);
        nlohmann::json jobs = nlohmann::json::array();
        for (std::size_t i = 0; i < page.size() && i < static_cast<std::size_t>(limit); ++i) {
          jobs.push_back(summary(page[i], pool));
        }
        nlohmann::json next = nullptr;
        if (page.size() > static_cast<std::size_t>(limit))
          next = std::to_string(page[static_cast<std::size_t>(limit) - 1].seq);
        sendJson(res, 200, {{"jobs", jobs}, {"next_cursor", next}});
      });
  http.route({"GET",
              std::string(kJobs) + "/{id}",
              {{"summary", "A job's status, progress and, when finished, its report"},
               {"tags", {"jobs"}},
               {"responses",
                {{"200", jsonResponse("The job.", schemaRef("JobStatus"))}, {"404", notFound}}}}},
             [&](const httplib::Request& req, httplib::Response& res) {
               sendJsonText(res, 200, statusText(findJob(store, req), pool));
             });
  http.route(
      {"GET",
       std::string(kJobs) + "/{id}/job",
       {{"summary", "The job document as accepted (a registered machine inlined)"},
        {"tags", {"jobs"}},
        {"description", "What the job ran: lets a client show the program lines a report names."},
        {"responses",
         {{"200", jsonResponse("The job document.", schemaRef("Job"))}, {"404", notFound}}}}},
      [&](const httplib::Request& req, httplib::Response& res) {
        sendJsonText(res, 200, findJob(store, req, true).job);
      });
  http.route(
      {"GET",
       std::string(kJobs) + "/{id}/mesh",
       {{"summary", "The final stock as binary STL (mm, workpiece frame)"},
        {"tags", {"jobs"}},
        {"parameters",
         {{{"name", "id"}, {"in", "path"}, {"required", true}, {"schema", {{"type", "string"}}}},
          {{"name", "Range"},
           {"in", "header"},
           {"description",
            "One byte range (`bytes=0-99`, `bytes=1000-`, `bytes=-500`) resumes a download "
            "(206); several ranges or another unit get the whole file (200)."},
           {"schema", {{"type", "string"}}}}}},
        {"responses",
         {{"200",
           {{"description", "Binary STL."},
            {"content",
             {{"model/stl", {{"schema", {{"type", "string"}, {"format", "binary"}}}}}}}}},
          {"206",
           {{"description", "The requested byte range (Content-Range)."},
            {"content",
             {{"model/stl", {{"schema", {{"type", "string"}, {"format", "binary"}}}}}}}}},
          {"404", notFound},
          {"416", errorResponse("The range starts past the end (`range_not_satisfiable`; "
                                "Content-Range `bytes */size`).")},
          {"409", errorResponse("No mesh: not done, failed, or not written (`mesh_too_large`, "
                                "`mesh_write_failed`).")}}}}},
      [&](const httplib::Request& req, httplib::Response& res) { sendMesh(req, res, store); });
  http.route({"DELETE",
              std::string(kJobs) + "/{id}",
              {{"summary", "Cancel a queued or running job; delete a finished one"},
               {"tags", {"jobs"}},
               {"responses",
                {{"200", jsonResponse("Cancelled (a running job stops within a step).",
                                      {{"type", "object"}})},
                 {"202", jsonResponse("Cancel requested; still stopping.", {{"type", "object"}})},
                 {"204", {{"description", "Deleted with its report and mesh."}}},
                 {"404", notFound}}}}},
             [&](const httplib::Request& req, httplib::Response& res) {
               deleteJob(req, res, store, pool);
             });
}

}  // namespace mdhd::service

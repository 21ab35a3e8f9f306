#pragma once
// Durable state of the service in SQLite (WAL, synchronous FULL: a commit is on
// disk when it returns): jobs with their status, timestamps and reports, the
// machine registry, and a few flags; final meshes are files beside the database
// (meshes/<id>.stl, written under a temporary name and renamed). Every method is
// one transaction; the store is shared by request and worker threads.
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "daemon/sqlite_db.h"

namespace mdhd::service {

struct JobRecord {
  std::int64_t seq = 0;  // acceptance order
  std::string id;
  std::string status;  // queued running done failed cancelled
  std::string machine_name;
  std::string created_at;
  std::string started_at;
  std::string finished_at;
  int attempts = 0;                   // times a worker started it
  int interrupted = 0;                // times the process died while it ran
  std::optional<std::string> report;  // JSON text, when done or failed
  bool mesh = false;
  // Why a done job has no mesh: {"code": "mesh_too_large"|"mesh_write_failed",
  // "message": ...} as JSON text, or "".
  std::string mesh_error;
  std::string job;  // the job JSON text (machine inlined), when asked for
};

struct MachineRecord {
  std::string name;
  std::string machine;  // JSON text
  std::string updated_at;
};

class JobStore {
 public:
  // Opens or creates `dir`/mdhd.sqlite3 and `dir`/meshes. Throws on failure.
  // Throws when another process holds the folder (one service per data folder).
  explicit JobStore(const std::filesystem::path& dir);
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  // A new queued job, committed when this returns.
  void insertJob(const std::string& id, const std::string& jobJson, const std::string& machineName);
  std::optional<JobRecord> job(const std::string& id, bool withJobText = false);
  // Newest first; `beforeSeq` > 0 continues a page.
  std::vector<JobRecord> jobs(int limit, std::int64_t beforeSeq);
  void markRunning(const std::string& id);
  // Final status (done, failed, cancelled) with the report text if any, and why
  // there is no mesh (JobRecord::mesh_error).
  void finishJob(const std::string& id, const std::string& status,
                 const std::optional<std::string>& report, bool mesh,
                 const std::string& meshError = "");
  // Cancelled, only if still queued or running (a job that finished meanwhile keeps its
  // report). True when it was cancelled here.
  bool cancelUnfinished(const std::string& id);
  // Back to queued (shutdown or restart): started_at cleared, attempts kept.
  void requeue(const std::string& id);
  // Removes a job and its mesh; false when there was none.
  bool deleteJob(const std::string& id);
  // On start: jobs left running by a dead process are queued again, unless they
  // have now been interrupted `maxInterruptions` times: those (a job that brings
  // the process down would otherwise do it forever) fail with `failedReport`.
  // Returns every queued job id, oldest first.
  std::vector<std::string> recoverQueued(int maxInterruptions, const std::string& failedReport);
  std::int64_t countByStatus(const std::string& status);

  std::filesystem::path meshPath(const std::string& id) const;

  // Machines: true when `name` was new.
  bool putMachine(const std::string& name, const std::string& machineJson);
  std::optional<MachineRecord> machine(const std::string& name);
  std::vector<MachineRecord> machines();
  bool deleteMachine(const std::string& name);

  // One-time markers (e.g. example machines registered).
  bool flag(const std::string& key);
  void setFlag(const std::string& key);

 private:
  // flock on <dir>/lock, held until after the database is closed (members go in
  // reverse order) and released by the kernel if the process dies.
  struct FolderLock {
    explicit FolderLock(const std::filesystem::path& dir);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;
    int fd = -1;
  };

  std::filesystem::path dir_;
  FolderLock lock_;
  std::mutex mutex_;
  SqliteDb db_;
};

// A fresh job id: 32 lowercase hex digits from the system's random source.
std::string newJobId();
// Whether `id` has that shape (checked before it names anything).
bool isJobId(const std::string& id);
// Machine names: 1-64 of [A-Za-z0-9._-], starting with a letter or digit.
bool isMachineName(const std::string& name);

}  // namespace mdhd::service

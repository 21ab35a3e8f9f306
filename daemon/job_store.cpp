#include "daemon/job_store.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <random>
#include <stdexcept>

#include "daemon/json_log.h"

namespace mdhd::service {
namespace {

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS jobs (
  seq INTEGER PRIMARY KEY AUTOINCREMENT,
  id TEXT NOT NULL UNIQUE,
  status TEXT NOT NULL,
  machine_name TEXT NOT NULL DEFAULT '',
  job TEXT NOT NULL,
  created_at TEXT NOT NULL,
  started_at TEXT,
  finished_at TEXT,
  attempts INTEGER NOT NULL DEFAULT 0,
  interrupted INTEGER NOT NULL DEFAULT 0,
  report TEXT,
  mesh INTEGER NOT NULL DEFAULT 0,
  mesh_error TEXT NOT NULL DEFAULT ''
);
CREATE INDEX IF NOT EXISTS jobs_status ON jobs(status);
CREATE TABLE IF NOT EXISTS machines (
  name TEXT PRIMARY KEY,
  machine TEXT NOT NULL,
  updated_at TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS flags (key TEXT PRIMARY KEY);
)sql";

constexpr const char* kJobColumns =
    "seq, id, status, machine_name, created_at, started_at, finished_at, attempts, report, mesh, "
    "interrupted, mesh_error";

JobRecord readJob(const Statement& s) {
  JobRecord r;
  r.seq = s.integer(0);
  r.id = s.text(1);
  r.status = s.text(2);
  r.machine_name = s.text(3);
  r.created_at = s.text(4);
  r.started_at = s.text(5);
  r.finished_at = s.text(6);
  r.attempts = static_cast<int>(s.integer(7));
  r.report = s.optionalText(8);
  r.mesh = s.integer(9) != 0;
  r.interrupted = static_cast<int>(s.integer(10));
  r.mesh_error = s.text(11);
  return r;
}

std::filesystem::path prepareDir(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir / "meshes");
  return dir;
}

// Meshes half written when a process died (their jobs run again and write anew).
void removePartialMeshes(const std::filesystem::path& meshes) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(meshes, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 8 && name.compare(name.size() - 8, 8, ".partial") == 0) {
      std::error_code ignored;
      std::filesystem::remove(entry.path(), ignored);
    }
  }
}

}  // namespace

JobStore::JobStore(const std::filesystem::path& dir)
    : dir_(prepareDir(dir)), lock_(dir_), db_((dir / "mdhd.sqlite3").string()) {
  db_.exec("PRAGMA journal_mode=WAL");
  // FULL: a commit (the 202 of an accepted job) survives power loss, not only a crash.
  db_.exec("PRAGMA synchronous=FULL");
  db_.exec(kSchema);
  // Stores made before mesh_error existed.
  bool hasMeshError = true;
  {
    Statement column(db_,
                     "SELECT COUNT(*) FROM pragma_table_info('jobs') WHERE name = 'mesh_error'");
    hasMeshError = column.step() && column.integer(0) > 0;
  }
  if (!hasMeshError) db_.exec("ALTER TABLE jobs ADD COLUMN mesh_error TEXT NOT NULL DEFAULT ''");
  removePartialMeshes(dir_ / "meshes");  // the folder lock is ours: no writer is left
}

JobStore::FolderLock::FolderLock(const std::filesystem::path& dir) {
  const std::filesystem::path path = dir / "lock";
  fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) throw std::runtime_error("cannot open " + path.string());
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    close(fd);
    throw std::runtime_error("another mdhd serve is using the data folder " + dir.string());
  }
}

JobStore::FolderLock::~FolderLock() {
  close(fd);
}

void JobStore::insertJob(const std::string& id, const std::string& jobJson,
                         const std::string& machineName) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_,
              "INSERT INTO jobs (id, status, machine_name, job, created_at) "
              "VALUES (?, 'queued', ?, ?, ?)");
  s.bind(1, id).bind(2, machineName).bind(3, jobJson).bind(4, utcTimestamp()).run();
}

std::optional<JobRecord> JobStore::job(const std::string& id, bool withJobText) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kJobColumns + ", job FROM jobs WHERE id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  JobRecord r = readJob(s);
  if (withJobText) r.job = s.text(12);
  return r;
}

std::vector<JobRecord> JobStore::jobs(int limit, std::int64_t beforeSeq) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kJobColumns +
                       " FROM jobs WHERE seq < ? ORDER BY seq DESC LIMIT ?");
  s.bind(1, beforeSeq > 0 ? beforeSeq : INT64_MAX).bind(2, static_cast<std::int64_t>(limit));
  std::vector<JobRecord> out;
  while (s.step()) out.push_back(readJob(s));
  return out;
}

void JobStore::markRunning(const std::string& id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_,
              "UPDATE jobs SET status = 'running', started_at = ?, attempts = attempts + 1 "
              "WHERE id = ?");
  s.bind(1, utcTimestamp()).bind(2, id).run();
}

void JobStore::finishJob(const std::string& id, const std::string& status,
                         const std::optional<std::string>& report, bool mesh,
                         const std::string& meshError) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_,
              "UPDATE jobs SET status = ?, finished_at = ?, report = ?, mesh = ?, mesh_error = ? "
              "WHERE id = ?");
  s.bind(1, status).bind(2, utcTimestamp());
  if (report) {
    s.bind(3, *report);
  } else {
    s.bindNull(3);
  }
  s.bind(4, static_cast<std::int64_t>(mesh ? 1 : 0)).bind(5, meshError).bind(6, id).run();
}

bool JobStore::cancelUnfinished(const std::string& id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_,
              "UPDATE jobs SET status = 'cancelled', finished_at = ? "
              "WHERE id = ? AND status IN ('queued', 'running')");
  s.bind(1, utcTimestamp()).bind(2, id).run();
  return db_.changes() > 0;
}

void JobStore::requeue(const std::string& id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "UPDATE jobs SET status = 'queued', started_at = NULL WHERE id = ?");
  s.bind(1, id).run();
}

bool JobStore::deleteJob(const std::string& id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "DELETE FROM jobs WHERE id = ?");
  s.bind(1, id).run();
  const bool removed = db_.changes() > 0;
  std::error_code ignored;
  std::filesystem::remove(meshPath(id), ignored);
  return removed;
}

std::vector<std::string> JobStore::recoverQueued(int maxInterruptions,
                                                 const std::string& failedReport) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Transaction t(db_);
  db_.exec(
      "UPDATE jobs SET status = 'queued', started_at = NULL, interrupted = interrupted + 1 "
      "WHERE status = 'running'");
  Statement poisoned(db_,
                     "UPDATE jobs SET status = 'failed', finished_at = ?, report = ? "
                     "WHERE status = 'queued' AND interrupted >= ?");
  poisoned.bind(1, utcTimestamp()).bind(2, failedReport);
  poisoned.bind(3, static_cast<std::int64_t>(maxInterruptions)).run();
  Statement s(db_, "SELECT id FROM jobs WHERE status = 'queued' ORDER BY seq");
  std::vector<std::string> ids;
  while (s.step()) ids.push_back(s.text(0));
  t.commit();
  return ids;
}

std::int64_t JobStore::countByStatus(const std::string& status) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "SELECT COUNT(*) FROM jobs WHERE status = ?");
  s.bind(1, status);
  return s.step() ? s.integer(0) : 0;
}

std::filesystem::path JobStore::meshPath(const std::string& id) const {
  return dir_ / "meshes" / (id + ".stl");
}

bool JobStore::putMachine(const std::string& name, const std::string& machineJson) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Transaction t(db_);
  Statement exists(db_, "SELECT 1 FROM machines WHERE name = ?");
  exists.bind(1, name);
  const bool created = !exists.step();
  Statement s(db_,
              "INSERT INTO machines (name, machine, updated_at) VALUES (?, ?, ?) "
              "ON CONFLICT(name) DO UPDATE SET machine = excluded.machine, "
              "updated_at = excluded.updated_at");
  s.bind(1, name).bind(2, machineJson).bind(3, utcTimestamp()).run();
  t.commit();
  return created;
}

std::optional<MachineRecord> JobStore::machine(const std::string& name) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "SELECT name, machine, updated_at FROM machines WHERE name = ?");
  s.bind(1, name);
  if (!s.step()) return std::nullopt;
  return MachineRecord{s.text(0), s.text(1), s.text(2)};
}

std::vector<MachineRecord> JobStore::machines() {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "SELECT name, machine, updated_at FROM machines ORDER BY name");
  std::vector<MachineRecord> out;
  while (s.step()) out.push_back({s.text(0), s.text(1), s.text(2)});
  return out;
}

bool JobStore::deleteMachine(const std::string& name) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "DELETE FROM machines WHERE name = ?");
  s.bind(1, name).run();
  return db_.changes() > 0;
}

bool JobStore::flag(const std::string& key) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "SELECT 1 FROM flags WHERE key = ?");
  s.bind(1, key);
  return s.step();
}

void JobStore::setFlag(const std::string& key) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, "INSERT OR IGNORE INTO flags (key) VALUES (?)");
  s.bind(1, key).run();
}

std::string newJobId() {
  static std::mutex mutex;
  static std::random_device device;  // /dev/urandom on Linux
  const std::lock_guard<std::mutex> lock(mutex);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id;
  for (int i = 0; i < 4; ++i) {
    std::uint32_t v = device();
    for (int k = 0; k < 8; ++k, v >>= 4) id += kHex[v & 15u];
  }
  return id;
}

bool isJobId(const std::string& id) {
  if (id.size() != 32) return false;
  for (char c : id) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

bool isMachineName(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    const bool alnum = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    if (!alnum && (i == 0 || (c != '.' && c != '_' && c != '-'))) return false;
  }
  return true;
}

}  // namespace mdhd::service

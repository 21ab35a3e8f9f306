// A shadow's life cycle and what it shows: construction, start/stop, status,
// alarms, mesh. The three threads are in shadow_session_threads.cpp.
#include "daemon/shadow_session.h"

#include <sstream>

#include "protocol/report_json.h"
#include "protocol/stl.h"
#include "sim/mesh/mesher.h"

namespace mdhd::shadow {

const char* shadowStateName(ShadowState state) {
  switch (state) {
    case ShadowState::kConnecting:
      return "connecting";
    case ShadowState::kLive:
      return "live";
    case ShadowState::kStale:
      return "stale";
    case ShadowState::kStopped:
      return "stopped";
  }
  return "?";
}

ShadowSession::ShadowSession(std::string id, ShadowSpec spec, SessionOptions options,
                             SourceFactory source)
    : id_(std::move(id)),
      spec_(std::move(spec)),
      options_(options),
      source_factory_(std::move(source)),
      created_(SteadyClock::now()) {
  if (!source_factory_) {
    source_factory_ = [](const protocol::ModbusMap& map) {
      return std::make_unique<protocol::ModbusTcpClient>(map);
    };
  }
  kin_ = std::make_unique<kin::Kinematics>(*spec_.job.machine);
  if (spec_.job.program) track_ = std::make_unique<ProgramTrack>(spec_.job, *kin_);
  carver_ = std::make_unique<ShadowCarver>(spec_.job, *kin_, track_.get());
  // A contact is alarmed from inside the motion that makes it, before its depth is
  // measured and the motion finished: the depth follows in an alarm_update.
  carver_->setAlarmListener([this](const check::Collision& c, std::size_t episode) {
    raise({false, c, 0.0, episode, 0, false});
  });
  if (!spec_.map.line) options_.lookahead = false;  // the program cannot be followed
  if (spec_.job.tools.size() == 1) tool_hint_ = spec_.job.tools.front().number;
  watchdog_ = std::chrono::duration_cast<SteadyClock::duration>(
      std::chrono::duration<double>(1.0 / spec_.map.poll_hz) +
      std::chrono::milliseconds(spec_.map.timeout_ms));
  report_dirty_ = true;
  refreshReport(std::chrono::milliseconds(0));  // the raw stock's
}

ShadowSession::~ShadowSession() {
  stop();
}

void ShadowSession::start() {
  std::lock_guard lock(mutex_);
  if (started_) return;
  started_ = true;
  events_.publish("state", {{"state", "connecting"}});
  poll_ = std::thread([this] { pollLoop(); });
  carve_ = std::thread([this] { carveLoop(); });
  if (track_ && options_.lookahead) ahead_ = std::thread([this] { aheadLoop(); });
}

void ShadowSession::stop() {
  std::lock_guard once(stop_mutex_);  // two callers must not join the same threads
  if (state_.load() == ShadowState::kStopped) return;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  {
    // A poll blocked on the network (a peer that never answers) ends now.
    std::lock_guard lock(source_mutex_);
    if (source_ != nullptr) source_->interrupt();
  }
  for (std::thread* t : {&poll_, &carve_, &ahead_})
    if (t->joinable()) t->join();
  refreshReport(std::chrono::milliseconds(0));  // the last state is exact
  setState(ShadowState::kStopped, "stopped");
  events_.close();
  settled_.notify_all();
}

void ShadowSession::setState(ShadowState s, const std::string& reason) {
  if (state_.exchange(s) == s) return;
  nlohmann::json j = {{"state", shadowStateName(s)}};
  if (!reason.empty()) j["reason"] = reason;
  events_.publish("state", j);
}

void ShadowSession::raise(Alarm alarm) {
  nlohmann::json j;
  {
    std::lock_guard lock(mutex_);
    alarm.id = alarms_raised_++;
    j = alarmToJson(alarm, *spec_.job.machine);
    alarms_.push_back(std::move(alarm));
    if (alarms_.size() > kKeepFirstAlarms + kKeepLastAlarms) {
      alarms_.erase(alarms_.begin() + static_cast<std::ptrdiff_t>(kKeepFirstAlarms));
      ++counters_.alarms_dropped;
    }
  }
  events_.publish("alarm", j);
  if (spec_.map.feed_hold.enabled) hold_pending_ = true;
}

ShadowCounters ShadowSession::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

std::vector<Alarm> ShadowSession::alarms() const {
  std::lock_guard lock(mutex_);
  return alarms_;
}

nlohmann::json ShadowSession::poseJson(const PollSample& s, int tool) const {
  const geom::Tool* t = spec_.job.findTool(tool);
  nlohmann::json j = poseToJson(s.joints, *kin_, t != nullptr ? t->length : 0.0);
  j["tool"] = tool;
  j["line"] = s.line ? nlohmann::json(*s.line) : nlohmann::json(nullptr);
  j["spindle_on"] = s.spindle_on ? nlohmann::json(*s.spindle_on) : nlohmann::json(nullptr);
  return j;
}

nlohmann::json ShadowSession::status() const {
  nlohmann::json j;
  {
    std::lock_guard lock(mutex_);
    j = {{"id", id_}, {"state", shadowStateName(state_.load())}};
    if (latest_) {
      j.update(poseJson(*latest_, latest_->tool.value_or(tool_hint_)));
    } else {
      j.update(poseToJson(spec_.job.machine->home, *kin_, 0.0));
      j["tool"] = nullptr;
      j["line"] = nullptr;
      j["spindle_on"] = nullptr;
    }
    j["samples"] = counters_.polls_ok;
    nlohmann::json alarms = nlohmann::json::array();
    for (const Alarm& a : alarms_) alarms.push_back(alarmToJson(a, *spec_.job.machine));
    j["alarms"] = std::move(alarms);
    const ShadowCounters& c = counters_;
    j["alarms_dropped"] = c.alarms_dropped;
    const auto text = [](const std::string& t) {
      return t.empty() ? nlohmann::json(nullptr) : nlohmann::json(t);
    };
    j["polls"] = {{"ok", c.polls_ok},
                  {"failed", c.polls_failed},
                  {"backoff", c.polls_backoff},
                  {"poll_hz", spec_.map.poll_hz},
                  {"last_error", text(last_error_)}};
    j["carving"] = {
        {"motions", c.motions},    {"merged", c.merged},   {"motion_errors", c.motion_errors},
        {"thinned", c.thinned},    {"backlog", c.backlog}, {"max_backlog", c.max_backlog},
        {"lag_ms", c.carve_lag_ms}};
    j["carving"]["pending"] = polled_ - carved_;  // polled, not cut yet
    j["lookahead"] = {{"enabled", track_ != nullptr && options_.lookahead},
                      {"runs", c.lookaheads},
                      {"busy", ahead_busy_ || ahead_task_ != nullptr}};
    j["feed_hold"] = {{"enabled", spec_.map.feed_hold.enabled}, {"coil", spec_.map.feed_hold.coil},
                      {"writes", c.feed_hold_writes},           {"failures", c.feed_hold_failures},
                      {"pending", hold_pending_.load()},        {"error", text(feed_hold_error_)}};
  }
  {
    // Never sim_mutex_: a batch being cut must not hold up a GET.
    std::lock_guard lock(report_mutex_);
    j["report"] = report_;
    j["report_age_ms"] =
        std::chrono::duration<double, std::milli>(SteadyClock::now() - report_at_).count();
  }
  return j;
}

nlohmann::json ShadowSession::summary() const {
  std::lock_guard lock(mutex_);
  return {{"id", id_},
          {"state", shadowStateName(state_.load())},
          {"samples", counters_.polls_ok},
          {"host", spec_.map.host},
          {"port", spec_.map.port}};
}

void ShadowSession::refreshReport(std::chrono::milliseconds min_age) {
  {
    std::lock_guard lock(mutex_);
    if (!report_dirty_) return;
  }
  {
    std::lock_guard lock(report_mutex_);
    if (SteadyClock::now() - report_at_ < min_age) return;
  }
  nlohmann::json report;
  {
    // The report walks the stock: taken by the carve thread between batches.
    std::lock_guard lock(sim_mutex_);
    {
      std::lock_guard small(mutex_);
      report_dirty_ = false;  // a batch cut from here on marks it again
    }
    report = protocol::reportToJson(carver_->simulation().snapshot(0), &*spec_.job.machine);
  }
  {
    std::lock_guard lock(report_mutex_);
    report_ = std::move(report);
    report_at_ = SteadyClock::now();
  }
  settled_.notify_all();
}

cli::StlOutcome ShadowSession::stockStl(std::string& out, std::uint64_t maxBytes) const {
  std::unique_ptr<mdh::Stock> copy;
  {
    std::lock_guard lock(sim_mutex_);
    copy = carver_->simulation().stock().clone();
  }
  cli::StlLimits limits;
  limits.max_bytes = maxBytes;
  return cli::stockStlBytes(*copy, "mdhd shadow " + id_ + ": live stock (mm, workpiece frame)",
                            limits, out);
}

double ShadowSession::stockVolume() const {
  std::lock_guard lock(sim_mutex_);
  return carver_->simulation().stock().volume();
}

bool ShadowSession::waitIdle(std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  return settled_.wait_for(lock, timeout, [&] {
    return stopping_.load() ||
           (carved_ == polled_ && !ahead_busy_ && !ahead_task_ && !report_dirty_);
  });
}

}  // namespace mdhd::shadow

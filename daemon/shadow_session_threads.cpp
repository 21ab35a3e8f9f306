// The three threads of a shadow: polling (keeps its rhythm, never blocks on the
// carving), carving (cuts what was polled, raises alarms) and the look-ahead.
#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include "daemon/shadow_session.h"

namespace mdhd::shadow {
namespace {

using Seconds = std::chrono::duration<double>;

// How often the idle carve thread wakes: the watchdog and the report snapshot.
constexpr auto kCarveTick = std::chrono::milliseconds(50);
// The report snapshot is at most this old while samples keep coming; once none
// came for kCarveTick it is taken at once (if the stock changed).
constexpr auto kReportMaxAge = std::chrono::milliseconds(500);
// A failed feed-hold write is tried again after this, doubling per failure up to
// kHoldRetryMax: the polls go on between the tries, so a controller that
// ignores the write (each try a timeout) does not also blind the shadow.
constexpr auto kHoldRetryFirst = std::chrono::milliseconds(50);
constexpr auto kHoldRetryMax = std::chrono::milliseconds(2000);

class UnknownTool : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string toolList(const protocol::Job& job) {
  std::string out;
  for (const geom::Tool& t : job.tools) out += (out.empty() ? "" : ", ") + std::to_string(t.number);
  return out.empty() ? "none" : out;
}

}  // namespace

std::string ShadowSession::unknownTool(const PollSample& s) const {
  // Tool 0: the spindle is empty, nothing to cut.
  if (!s.tool || *s.tool == 0 || spec_.job.findTool(*s.tool) != nullptr) return "";
  return "the machine holds tool " + std::to_string(*s.tool) +
         ", which the job does not define (its tools: " + toolList(spec_.job) +
         "): its moves are neither cut nor checked until a tool of the job is in the spindle";
}

ShadowSession::HoldWrite ShadowSession::writeFeedHold(protocol::RegisterSource& source) {
  const nlohmann::json coil = spec_.map.feed_hold.coil;
  try {
    source.writeFeedHold(true);
    {
      std::lock_guard lock(mutex_);
      ++counters_.feed_hold_writes;
      feed_hold_error_.clear();
    }
    events_.publish("feed_hold", {{"ok", true}, {"coil", coil}});
    return HoldWrite::kWritten;
  } catch (const protocol::ModbusError& e) {
    if (e.kind() == protocol::ModbusError::Kind::kInterrupted)
      return HoldWrite::kNotTried;  // stopping
    hold_pending_ = true;           // again later
    // Waiting to reconnect is not a new failure: the one that started it stays.
    if (e.kind() == protocol::ModbusError::Kind::kBackoff) return HoldWrite::kNotTried;
    const std::string reason =
        std::string("feed_hold: ") + protocol::modbusErrorKindName(e.kind()) + ": " + e.what();
    bool first = false;
    {
      std::lock_guard lock(mutex_);
      ++counters_.feed_hold_failures;
      first = feed_hold_error_.empty();
      feed_hold_error_ = reason;
      last_error_ = reason;
    }
    // Once per run of failures (it is retried until it succeeds).
    if (first) events_.publish("feed_hold", {{"ok", false}, {"coil", coil}, {"error", reason}});
    return HoldWrite::kFailed;
  }
}

void ShadowSession::pollLoop() {
  std::unique_ptr<protocol::RegisterSource> source = source_factory_(spec_.map);
  {
    std::lock_guard lock(source_mutex_);
    source_ = source.get();
    if (stopping_.load()) source->interrupt();  // stop() came first
  }
  const auto period =
      std::chrono::duration_cast<SteadyClock::duration>(Seconds(1.0 / spec_.map.poll_hz));
  const auto bridge =
      std::max(std::chrono::duration_cast<SteadyClock::duration>(Seconds(options_.bridge_seconds)),
               3 * period);
  std::optional<SteadyClock::time_point> last_good;
  bool failing = false;
  SteadyClock::time_point next_pose{};
  const auto pose_every = std::chrono::duration_cast<SteadyClock::duration>(
      Seconds(1.0 / std::max(options_.pose_hz, 0.01)));
  auto next = SteadyClock::now();
  SteadyClock::time_point hold_retry_at{};  // after a failed write
  SteadyClock::duration hold_wait = kHoldRetryFirst;
  bool hold_after_read = false;  // a failed write is tried again after a good read
  while (!stopping_.load()) {
    // Before the read (the hold is what matters). A failed write is tried again
    // after its own backoff and a good read: a write that breaks the connection
    // (a timeout) would otherwise take every reconnection, and no read be made.
    if (hold_pending_.load() && !hold_after_read && SteadyClock::now() >= hold_retry_at &&
        hold_pending_.exchange(false)) {
      switch (writeFeedHold(*source)) {
        case HoldWrite::kWritten:
          hold_wait = kHoldRetryFirst;
          break;
        case HoldWrite::kFailed:
          hold_after_read = true;
          hold_retry_at = SteadyClock::now() + hold_wait;
          hold_wait = std::min<SteadyClock::duration>(2 * hold_wait, kHoldRetryMax);
          break;
        case HoldWrite::kNotTried:
          break;  // at the next poll
      }
    }
    try {
      const protocol::ModbusSample r = source->read();
      PollSample s{SteadyClock::now(), r.joints, r.tool, r.spindle_on, r.line, false};
      // Never silently blind: the poll counts as failed and the shadow is stale
      // until a tool of the job is in; the way back is a resync or a bridge.
      if (const std::string unknown = unknownTool(s); !unknown.empty()) throw UnknownTool(unknown);
      s.resync = !last_good || (failing && s.t - *last_good > bridge);
      failing = false;
      hold_after_read = false;
      last_good = s.t;
      onGoodPoll(s);
      if (s.t >= next_pose) {
        next_pose = s.t + pose_every;
        int tool = 0;
        {
          std::lock_guard lock(mutex_);
          tool = s.tool.value_or(tool_hint_);
        }
        nlohmann::json pose = poseJson(s, tool);
        pose["samples"] = counters().polls_ok;
        events_.publish("pose", pose);
      }
    } catch (const protocol::ModbusError& e) {
      if (e.kind() == protocol::ModbusError::Kind::kInterrupted) break;  // stop()
      failing = true;
      onBadPoll(protocol::modbusErrorKindName(e.kind()), e.what());
    } catch (const protocol::RegisterValueError& e) {
      failing = true;
      onBadPoll("bad_value", e.what());
    } catch (const UnknownTool& e) {
      failing = true;
      onBadPoll("unknown_tool", e.what());
    }
    next += period;
    const auto now = SteadyClock::now();
    // Late wake-ups are made up by polling at once; after a real stall (more than
    // 20 periods behind) the rhythm starts again from now instead of bursting.
    if (next < now - 20 * period) next = now;
    std::unique_lock lock(mutex_);
    wake_.wait_until(lock, next, [&] { return stopping_.load(); });
  }
  std::lock_guard lock(source_mutex_);
  source_ = nullptr;
}

void ShadowSession::onGoodPoll(PollSample& s) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(s);
    ++polled_;
    ++counters_.polls_ok;
    counters_.backlog = queue_.size();
    counters_.max_backlog = std::max<std::uint64_t>(counters_.max_backlog, queue_.size());
    latest_ = s;
  }
  wake_.notify_all();
  std::lock_guard lock(mutex_);  // against the watchdog
  if (state_.load() != ShadowState::kLive) setState(ShadowState::kLive, "");
}

void ShadowSession::onBadPoll(const std::string& kind, const std::string& what) {
  std::string reason = kind + ": " + what;
  std::lock_guard lock(mutex_);
  if (kind == "backoff") {
    // Not a new failure: the one that started the backoff stays in last_error.
    ++counters_.polls_backoff;
    if (!last_error_.empty()) reason = last_error_;
  } else {
    ++counters_.polls_failed;
    last_error_ = reason;
  }
  // Before the first answer the shadow is still connecting; after it, stale. An
  // unknown tool is an answer: the controller is there, the shadow is blind.
  const ShadowState now = state_.load();
  if (now == ShadowState::kLive || (now == ShadowState::kConnecting && kind == "unknown_tool"))
    setState(ShadowState::kStale, reason);
}

void ShadowSession::watchdog() {
  std::lock_guard lock(mutex_);
  if (state_.load() != ShadowState::kLive || !latest_) return;
  const auto quiet = SteadyClock::now() - latest_->t;
  if (quiet <= watchdog_) return;
  const auto ms = [](SteadyClock::duration d) {
    return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count());
  };
  setState(ShadowState::kStale, "watchdog: no good sample for " + ms(quiet) + " ms (poll period " +
                                    "plus timeout_ms: " + ms(watchdog_) + " ms)");
}

std::vector<PollSample> ShadowSession::thin(std::vector<PollSample> batch) {
  // Keeps every other sample, and every sample where the line, tool or spindle
  // changes or a resync starts, so no kind of move is merged into another.
  std::vector<PollSample> out;
  out.reserve(batch.size() / 2 + 2);
  for (std::size_t i = 0; i < batch.size(); ++i) {
    const PollSample& s = batch[i];
    const bool change = i == 0 || i + 1 == batch.size() || s.resync ||
                        s.line != batch[i - 1].line || s.tool != batch[i - 1].tool ||
                        s.spindle_on != batch[i - 1].spindle_on || batch[i + 1].resync ||
                        s.line != batch[i + 1].line;
    if (change || i % 2 == 0) out.push_back(s);
  }
  return out;
}

void ShadowSession::carveLoop() {
  for (;;) {
    std::vector<PollSample> batch;
    bool idle = false;  // no sample for kCarveTick
    {
      std::unique_lock lock(mutex_);
      idle = !wake_.wait_for(lock, kCarveTick, [&] { return stopping_.load() || !queue_.empty(); });
      if (stopping_.load()) return;
      batch.swap(queue_);
      counters_.backlog = 0;
    }
    watchdog();
    refreshReport(idle ? std::chrono::milliseconds(0) : kReportMaxAge);
    if (batch.empty()) continue;
    const std::size_t polled = batch.size();
    if (batch.size() > options_.max_backlog) {
      batch = thin(std::move(batch));
      std::lock_guard lock(mutex_);
      counters_.thinned += polled - batch.size();
    }
    CarveResult r;
    std::optional<std::size_t> cursor;
    std::vector<std::pair<double, int>> depths;  // of every episode so far
    std::vector<nlohmann::json> updates;         // alarms now measured (alarm_update)
    std::set<std::size_t> announced;             // episodes alarmed already
    {
      std::lock_guard lock(sim_mutex_);
      if (options_.while_carving) options_.while_carving();
      r = carver_->carve(batch);
      cursor = carver_->cursor();
      const std::vector<check::Collision>& all = carver_->simulation().collisions();
      for (const check::Collision& c : all) depths.emplace_back(c.depth, c.last_line);
      // Alarms raised from inside this carve: now measured and placed exactly.
      std::lock_guard alarms_lock(mutex_);
      for (Alarm& a : alarms_) {
        if (a.predicted || a.depth_measured || a.episode >= all.size()) continue;
        a.collision = all[a.episode];
        a.depth_measured = true;
        updates.push_back(alarmToJson(a, *spec_.job.machine));
      }
    }
    const std::size_t first_new = depths.size() - r.alarms.size();
    {
      std::lock_guard lock(mutex_);
      counters_.motions += static_cast<std::uint64_t>(r.motions);
      counters_.merged += static_cast<std::uint64_t>(r.merged);
      counters_.motion_errors += r.errors.size();
      if (!r.errors.empty()) last_error_ = "motion: " + r.errors.back();
      counters_.carve_lag_ms =
          std::chrono::duration<double, std::milli>(SteadyClock::now() - batch.back().t).count();
      cursor_ = cursor;
      if (cursor && track_) tool_hint_ = track_->at(*cursor).motion.tool;
      for (Alarm& a : alarms_) {
        if (a.predicted || a.episode >= depths.size()) continue;
        a.collision.depth = depths[a.episode].first;
        a.collision.last_line = depths[a.episode].second;
        announced.insert(a.episode);
      }
    }
    for (const nlohmann::json& u : updates) events_.publish("alarm_update", u);
    for (std::size_t i = 0; i < r.alarms.size(); ++i) {
      // Contacts are alarmed from inside the carve already; axis limits are not.
      if (announced.count(first_new + i) == 0) raise({false, r.alarms[i], 0.0, first_new + i});
    }
    maybeLookAhead();
    if (r.motions > 0 || !r.alarms.empty() || !r.errors.empty()) {
      std::lock_guard lock(mutex_);
      report_dirty_ = true;
    }
    refreshReport(kReportMaxAge);
    {
      std::lock_guard lock(mutex_);
      carved_ += polled;
    }
    settled_.notify_all();
  }
}

void ShadowSession::maybeLookAhead() {
  if (!track_ || !options_.lookahead) return;
  std::size_t index = 0;
  {
    std::lock_guard lock(mutex_);
    // One at a time, and once per program motion the machine enters.
    if (ahead_busy_ || !cursor_ || ahead_done_for_ == cursor_) return;
    index = *cursor_;
    ahead_busy_ = true;
    ahead_done_for_ = cursor_;
  }
  std::unique_ptr<check::Simulation> fork;
  gcode::AxisValues joints{};
  {
    std::lock_guard lock(sim_mutex_);
    fork = carver_->simulation().fork();
    joints = carver_->last()->joints;
  }
  {
    std::lock_guard lock(mutex_);
    ahead_task_ = std::move(fork);
    ahead_index_ = index;
    ahead_joints_ = joints;
  }
  wake_.notify_all();
}

void ShadowSession::aheadLoop() {
  for (;;) {
    std::unique_ptr<check::Simulation> sim;
    std::size_t index = 0;
    gcode::AxisValues joints{};
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_.load() || ahead_task_ != nullptr; });
      if (stopping_.load()) return;
      sim = std::move(ahead_task_);
      index = ahead_index_;
      joints = ahead_joints_;
    }
    sim->setCancelFlag(&stopping_);
    const auto found = [&](const PredictedContact& p) {
      const check::Collision& c = p.collision;
      {
        std::lock_guard lock(mutex_);
        // Once per contact and motion; not when the machine is past it or the
        // live carving already raised it.
        const auto key = std::make_tuple(static_cast<int>(c.type), static_cast<int>(c.part),
                                         c.fixture, p.motion);
        if (predicted_keys_.count(key) != 0 || (cursor_ && *cursor_ > p.motion)) return;
        const bool seen = std::any_of(alarms_.begin(), alarms_.end(), [&](const Alarm& a) {
          return !a.predicted && a.collision.type == c.type && a.collision.line == c.line;
        });
        if (seen) return;
        predicted_keys_.insert(key);
      }
      raise({true, c, p.seconds, 0});
    };
    try {
      lookAhead(*sim, *track_, *kin_, index, joints, options_.span, found);
    } catch (const check::Cancelled&) {
      return;
    }
    {
      std::lock_guard lock(mutex_);
      ahead_busy_ = false;
      ++counters_.lookaheads;
    }
    settled_.notify_all();
  }
}

}  // namespace mdhd::shadow

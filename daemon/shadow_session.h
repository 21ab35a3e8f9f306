#pragma once
// One live shadow (service.md, "Live shadowing over Modbus TCP"): a poll thread
// reads the controller at poll_hz into a queue; a carve thread cuts the motions
// between polls into the live stock and raises alarms; with the program and a
// line register, a look-ahead thread simulates the next motions on a fork of the
// stock and raises predicted alarms. Events (pose, alarm, state) go to an
// EventLog for the Server-Sent Events streams.
//
// States: connecting (no answer yet), live, stale (the last poll failed, or no
// good sample for a poll period plus timeout_ms: the client reconnects with
// backoff, the stock is kept), stopped. A shadow is live state in memory, not a
// durable job: it ends with stop() or the daemon.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "daemon/shadow_carver.h"
#include "daemon/shadow_events.h"
#include "daemon/shadow_json.h"
#include "daemon/shadow_lookahead.h"
#include "daemon/shadow_program.h"
#include "daemon/shadow_spec.h"
#include "daemon/stock_stl.h"
#include "protocol/modbus_client.h"

namespace mdhd::shadow {

enum class ShadowState { kConnecting, kLive, kStale, kStopped };
const char* shadowStateName(ShadowState state);

struct SessionOptions {
  double pose_hz = 20.0;  // pose events at most this often
  bool lookahead = true;  // with a program and a line register
  LookaheadSpan span;
  // A failed stretch of polls shorter than this (or than 3 poll periods) is
  // bridged by a straight joint move; after a longer one the shadow resyncs: it
  // cuts nothing into the first new pose (where the machine went is unknown).
  double bridge_seconds = 0.25;
  // Samples waiting to be cut beyond which every other one of a batch is dropped
  // (coarser chords) so that the carving catches up.
  std::size_t max_backlog = 100'000;
  // Tests only: called by the carve thread with the simulation held (sim_mutex_)
  // before it cuts each batch, to stand for a long batch.
  std::function<void()> while_carving;
};

// The alarms a shadow keeps: the first kKeepFirstAlarms and the latest
// kKeepLastAlarms; those in between are dropped (counted) on a looping program.
inline constexpr std::size_t kKeepFirstAlarms = 100;
inline constexpr std::size_t kKeepLastAlarms = 100;

struct ShadowCounters {
  std::uint64_t polls_ok = 0, polls_failed = 0;
  std::uint64_t polls_backoff = 0;  // polls skipped waiting to reconnect (not in polls_failed)
  std::uint64_t feed_hold_failures = 0;
  std::uint64_t alarms_dropped = 0;
  std::uint64_t motions = 0, merged = 0, motion_errors = 0, thinned = 0;
  std::uint64_t backlog = 0, max_backlog = 0;  // samples waiting to be cut
  std::uint64_t lookaheads = 0, feed_hold_writes = 0;
  double carve_lag_ms = 0.0;  // poll to cut, of the latest batch
};

class ShadowSession {
 public:
  using SourceFactory =
      std::function<std::unique_ptr<protocol::RegisterSource>(const protocol::ModbusMap&)>;

  // Builds the kinematics, the simulation and (with a program) the program track.
  // Throws std::invalid_argument or kin::KinematicsError for a cell the engine
  // cannot use and gcode::GcodeError for a program that does not interpret.
  // Nothing runs before start(). `source`: by default a ModbusTcpClient.
  ShadowSession(std::string id, ShadowSpec spec, SessionOptions options = {},
                SourceFactory source = {});
  ~ShadowSession();
  ShadowSession(const ShadowSession&) = delete;
  ShadowSession& operator=(const ShadowSession&) = delete;

  void start();
  // Stops polling and carving (the stock stays readable); idempotent. A poll
  // blocked on the network is interrupted (RegisterSource::interrupt); a batch
  // being cut is finished first.
  void stop();

  const std::string& id() const { return id_; }
  const ShadowSpec& spec() const { return spec_; }
  ShadowState state() const { return state_.load(); }
  EventLog& events() { return events_; }
  ShadowCounters counters() const;
  std::vector<Alarm> alarms() const;
  // The GET /api/v1/shadows/{id} document. Never waits for the carving: the
  // report in it is a snapshot the carve thread refreshes (report_age_ms).
  nlohmann::json status() const;
  // {"id", "state", "samples", "host", "port"}: an entry of GET /api/v1/shadows.
  nlohmann::json summary() const;
  // The live stock as binary STL in `out`, at most `maxBytes` (0: no cap); over it,
  // the outcome says kTooLarge and `out` is empty.
  cli::StlOutcome stockStl(std::string& out, std::uint64_t maxBytes) const;
  double stockVolume() const;
  // Waits until every sample polled so far is cut and the look-ahead is idle;
  // false on timeout. For tests and benchmarks.
  bool waitIdle(std::chrono::milliseconds timeout) const;

 private:
  void pollLoop();
  void carveLoop();
  void aheadLoop();
  void setState(ShadowState s, const std::string& reason);
  void onGoodPoll(PollSample& s);
  void onBadPoll(const std::string& kind, const std::string& what);
  // Writes the hold: written, failed, or not tried (the client waits to reconnect
  // or is interrupted).
  enum class HoldWrite { kWritten, kFailed, kNotTried };
  HoldWrite writeFeedHold(protocol::RegisterSource& source);
  // Live with no good sample for watchdog_: stale. Carve thread.
  void watchdog();
  // Takes a new report snapshot when the stock changed since the last one and
  // the last is older than `min_age`. Takes sim_mutex_.
  void refreshReport(std::chrono::milliseconds min_age);
  // The reason a sample's tool cannot be cut, empty when it can.
  std::string unknownTool(const PollSample& s) const;
  void raise(Alarm alarm);
  void refreshAlarmDepths();
  void maybeLookAhead();
  nlohmann::json poseJson(const PollSample& s, int tool) const;
  static std::vector<PollSample> thin(std::vector<PollSample> batch);

  std::string id_;
  ShadowSpec spec_;
  SessionOptions options_;
  SourceFactory source_factory_;
  std::unique_ptr<kin::Kinematics> kin_;
  std::unique_ptr<ProgramTrack> track_;
  SteadyClock::time_point created_;

  // The carving: carver_ (and the stock in it) under sim_mutex_.
  mutable std::mutex sim_mutex_;
  std::unique_ptr<ShadowCarver> carver_;

  // Small state under mutex_: queue, latest sample, alarms, counters.
  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;     // carve and look-ahead threads, stop
  mutable std::condition_variable settled_;  // waitIdle
  std::vector<PollSample> queue_;
  std::uint64_t polled_ = 0, carved_ = 0;
  std::optional<PollSample> latest_;
  std::optional<std::size_t> cursor_;  // program motion the carving is on
  std::string last_error_;             // the last real failure (never a backoff wait)
  std::string feed_hold_error_;        // the last failed feed-hold write, empty after a success
  std::vector<Alarm> alarms_;          // the first and the latest ones (kKeep*Alarms)
  std::size_t alarms_raised_ = 0;
  bool report_dirty_ = false;  // the stock changed since the report snapshot
  std::set<std::tuple<int, int, int, std::size_t>> predicted_keys_;
  ShadowCounters counters_;
  int tool_hint_ = 0;
  // Look-ahead hand-over.
  std::unique_ptr<check::Simulation> ahead_task_;
  std::size_t ahead_index_ = 0;
  gcode::AxisValues ahead_joints_{};
  bool ahead_busy_ = false;
  std::optional<std::size_t> ahead_done_for_;  // cursor of the last look-ahead
  SteadyClock::duration watchdog_{};           // poll period + timeout_ms

  // The report snapshot: written by the carve thread, read by status().
  mutable std::mutex report_mutex_;
  SteadyClock::time_point report_at_{};
  nlohmann::json report_;

  // The poll thread's source while it runs, for stop() to interrupt it.
  std::mutex source_mutex_;
  protocol::RegisterSource* source_ = nullptr;

  std::atomic<ShadowState> state_{ShadowState::kConnecting};
  std::atomic<bool> hold_pending_{false};
  std::atomic<bool> stopping_{false};
  EventLog events_;
  std::mutex stop_mutex_;
  std::thread poll_, carve_, ahead_;
  bool started_ = false;
};

}  // namespace mdhd::shadow

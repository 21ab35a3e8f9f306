#pragma once
// One live shadow (service.md, "Live shadowing over Modbus TCP"): a poll thread
// reads the controller at poll_hz into a queue; a carve thread cuts the motions
// between polls into the live stock and raises alarms; with the program and a
// line register, a look-ahead thread simulates the next motions on a fork of the
// stock and raises predicted alarms. Events (pose, alarm, state) go to an
// EventLog for the Server-Sent Events streams.
//
// States: connecting (no answer yet), live, stale (the last poll failed: the
// client reconnects with backoff, the stock is kept), stopped. A shadow is live
// state in memory, not a durable job: it ends with stop() or the daemon.
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
};

struct ShadowCounters {
  std::uint64_t polls_ok = 0, polls_failed = 0;
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
  // Stops polling and carving (the stock stays readable); idempotent.
  void stop();

  const std::string& id() const { return id_; }
  const ShadowSpec& spec() const { return spec_; }
  ShadowState state() const { return state_.load(); }
  EventLog& events() { return events_; }
  ShadowCounters counters() const;
  std::vector<Alarm> alarms() const;
  // The GET /api/v1/shadows/{id} document.
  nlohmann::json status() const;
  // The live stock as binary STL.
  std::string stockStl() const;
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
  void onBadPoll(const std::exception& e, const char* kind);
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
  std::string last_error_;
  std::vector<Alarm> alarms_;
  std::set<std::tuple<int, int, int, std::size_t>> predicted_keys_;
  ShadowCounters counters_;
  int tool_hint_ = 0;
  // Look-ahead hand-over.
  std::unique_ptr<check::Simulation> ahead_task_;
  std::size_t ahead_index_ = 0;
  gcode::AxisValues ahead_joints_{};
  bool ahead_busy_ = false;
  std::optional<std::size_t> ahead_done_for_;  // cursor of the last look-ahead
  mutable std::optional<std::pair<SteadyClock::time_point, nlohmann::json>> report_cache_;

  std::atomic<ShadowState> state_{ShadowState::kConnecting};
  std::atomic<bool> hold_pending_{false};
  std::atomic<bool> stopping_{false};
  EventLog events_;
  std::mutex stop_mutex_;
  std::thread poll_, carve_, ahead_;
  bool started_ = false;
};

}  // namespace mdhd::shadow

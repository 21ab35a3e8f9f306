#include "daemon/shadow_carver.h"

#include <algorithm>
#include <limits>

#include "daemon/check_runner.h"

namespace mdhd::shadow {
namespace {

bool sameJoints(const gcode::AxisValues& a, const gcode::AxisValues& b) {
  return a == b;
}

// Whether b lies on the segment from a to c, strictly before c: a motion a -> b
// may then be extended to c without changing the swept path.
bool onTheWay(const gcode::AxisValues& a, const gcode::AxisValues& b, const gcode::AxisValues& c) {
  double dd = 0.0, db = 0.0;
  for (int i = 0; i < gcode::kAxisCount; ++i) {
    const double d = c[i] - a[i];
    dd += d * d;
    db += d * (b[i] - a[i]);
  }
  if (!(dd > 0.0)) return false;
  const double t = db / dd;
  if (!(t > 0.0 && t < 1.0)) return false;
  double off = 0.0;
  for (int i = 0; i < gcode::kAxisCount; ++i) {
    const double d = b[i] - (a[i] + t * (c[i] - a[i]));
    off += d * d;
  }
  return off <= kStraightTolerance * kStraightTolerance;
}

}  // namespace

ShadowCarver::ShadowCarver(const protocol::Job& job, const kin::Kinematics& kin,
                           const ProgramTrack* track)
    : job_(job), track_(track) {
  sim_ = std::make_unique<check::Simulation>(kin, job.tools, job.stock, cli::fixtureSolids(job),
                                             cli::simulationOptions(job.options));
}

void ShadowCarver::setAlarmListener(
    std::function<void(const check::Collision&, std::size_t episode)> listener) {
  if (!listener) {
    sim_->setContactListener(nullptr);
    return;
  }
  sim_->setContactListener([this, listener = std::move(listener)](std::size_t episode) {
    listener(sim_->collisions()[episode], episode);
  });
}

int ShadowCarver::toolOf(const PollSample& s) const {
  if (s.tool) return *s.tool;
  if (track_ != nullptr && cursor_) return track_->at(*cursor_).motion.tool;
  return job_.tools.size() == 1 ? job_.tools.front().number : 0;
}

ShadowCarver::Kind ShadowCarver::kindOf(const PollSample& s) {
  Kind k;
  if (s.line) {
    k.line = std::min<std::int64_t>(*s.line, std::numeric_limits<int>::max());
    if (track_ != nullptr) {
      if (const auto at = track_->locate(*s.line, s.joints, cursor_.value_or(0))) cursor_ = at;
    }
  }
  const TrackedMotion* programmed =
      track_ != nullptr && cursor_ && s.line ? &track_->at(*cursor_) : nullptr;
  if (programmed != nullptr && programmed->motion.pos.line != k.line) programmed = nullptr;
  if (programmed != nullptr && programmed->motion.type == gcode::MotionType::kRapid)
    k.type = gcode::MotionType::kRapid;
  k.tool = toolOf(s);
  // Unknown spindle state counts as running: a guess never raises spindle_off_cut.
  if (s.spindle_on) {
    k.spindle = *s.spindle_on ? gcode::SpindleState::kClockwise : gcode::SpindleState::kOff;
  } else if (programmed != nullptr) {
    k.spindle = programmed->motion.spindle;
  }
  return k;
}

void ShadowCarver::cut(const PollSample& from, const PollSample& to, const Kind& kind,
                       CarveResult& out) {
  gcode::Motion m;
  m.type = kind.type;
  m.pos.line = static_cast<int>(kind.line);
  if (track_ != nullptr) m.block_text = &track_->blockText(kind.line);
  m.start = from.joints;
  m.end = to.joints;
  m.tool = kind.tool;
  m.spindle = kind.spindle;
  const double seconds = std::max(0.0, std::chrono::duration<double>(to.t - from.t).count());
  // The machine moves a thin tool anyway, so it is carved; said once per tool.
  if (const std::string& blind = sim_->blindReason(m.tool);
      !blind.empty() && blind_said_.insert(m.tool).second)
    out.errors.push_back("line " + std::to_string(kind.line) + ": " + blind +
                         " (carved, its contacts not alarmed)");
  try {
    sim_->machineMotion(m, seconds);
  } catch (const gcode::GcodeError& e) {
    out.errors.push_back("line " + std::to_string(kind.line) + ": " + e.what());
  }
  ++out.motions;
  const std::vector<check::Collision>& all = sim_->collisions();
  for (; alarms_seen_ < all.size(); ++alarms_seen_) out.alarms.push_back(all[alarms_seen_]);
}

CarveResult ShadowCarver::carve(std::span<const PollSample> batch) {
  CarveResult out;
  // The motion being built: from `start` to `end`, extended while samples stay on
  // its straight line with the same kind.
  std::optional<PollSample> start, end;
  Kind kind;
  auto flush = [&] {
    if (!start || !end) return;
    cut(*start, *end, kind, out);
    start = end;
    end.reset();
  };
  for (const PollSample& s : batch) {
    if (!last_ || s.resync) {
      flush();
      last_ = s;
      start = s;
      end.reset();
      last_kind_ = kindOf(s);  // also places the cursor
      continue;
    }
    if (!start) start = last_;
    const Kind here = kindOf(s);
    // A controller starts a rapid and stops the spindle only between motions, so a
    // move between two polls that spans such a change is taken as the feed with the
    // spindle on: a rapid needs both ends on rapids, spindle off both ends off.
    Kind k = here;
    if (last_kind_.type != gcode::MotionType::kRapid) k.type = gcode::MotionType::kFeed;
    if (last_kind_.spindle != gcode::SpindleState::kOff) k.spindle = last_kind_.spindle;
    last_kind_ = here;
    const PollSample& tip = end ? *end : *start;
    if (sameJoints(tip.joints, s.joints)) {
      last_ = s;
      continue;  // standing still: nothing to cut
    }
    if (end && k == kind && onTheWay(start->joints, end->joints, s.joints)) {
      end = s;
      ++out.merged;
    } else {
      flush();
      end = s;
      kind = k;
    }
    last_ = s;
  }
  flush();
  return out;
}

}  // namespace mdhd::shadow

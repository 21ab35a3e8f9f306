#include "daemon/shadow_program.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "daemon/job_files.h"
#include "sim/gcode/interpreter.h"
#include "sim/kinematics/motion_time.h"

namespace mdhd::shadow {
namespace {

struct TrackFull {};

class Recorder : public gcode::MotionSink {
 public:
  Recorder(const protocol::Job& job, const kin::Kinematics& kin, std::vector<TrackedMotion>& out)
      : job_(job), kin_(kin), out_(out) {}

  void motion(const gcode::Motion& m) override {
    if (out_.size() >= kMaxTrackedMotions) throw TrackFull{};
    TrackedMotion t{m, 0.0, 0.0, pause_};
    t.motion.block_text = nullptr;
    if (const geom::Tool* tool = job_.findTool(m.tool)) t.tool_length = tool->length;
    try {
      t.seconds = kin::motionSeconds(m, kin_, t.tool_length);
    } catch (const kin::MotionTimeError& e) {
      throw gcode::GcodeError(m.pos, std::string("cannot time this move: ") + e.what());
    } catch (const kin::KinematicsError& e) {
      throw gcode::GcodeError(m.pos, std::string("cannot simulate this move: ") + e.what());
    }
    pause_ = 0.0;
    out_.push_back(std::move(t));
  }
  void event(const gcode::Event& e) override { pause_ += kin::eventSeconds(e); }

 private:
  const protocol::Job& job_;
  const kin::Kinematics& kin_;
  std::vector<TrackedMotion>& out_;
  double pause_ = 0.0;
};

// Squared distance in joint space from q to the chord of a motion.
double chordDistance2(const gcode::Motion& m, const gcode::AxisValues& q) {
  double dd = 0.0, dq = 0.0;
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    const double d = m.end[a] - m.start[a];
    dd += d * d;
    dq += d * (q[a] - m.start[a]);
  }
  const double t = dd > 0.0 ? std::clamp(dq / dd, 0.0, 1.0) : 0.0;
  double r = 0.0;
  for (int a = 0; a < gcode::kAxisCount; ++a) {
    const double d = q[a] - (m.start[a] + t * (m.end[a] - m.start[a]));
    r += d * d;
  }
  return r;
}

}  // namespace

ProgramTrack::ProgramTrack(const protocol::Job& job, const kin::Kinematics& kin) {
  cli::LoadedJob loaded;
  loaded.job = job;
  gcode::InterpreterConfig config = cli::interpreterConfig(loaded);
  config.subroutine_loader = [](std::string_view) -> std::unique_ptr<gcode::LineSource> {
    return nullptr;
  };
  Recorder recorder(job, kin, motions_);
  try {
    gcode::Interpreter(config, recorder).run(gcode::makeStringSource(*job.program));
  } catch (const TrackFull&) {
    truncated_ = true;
  }
  for (std::size_t i = 0; i < motions_.size(); ++i)
    if (motions_[i].motion.pos.file.empty()) by_line_[motions_[i].motion.pos.line].push_back(i);
  std::istringstream in(*job.program);
  for (std::string text; std::getline(in, text);) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    lines_.push_back(std::move(text));
  }
}

std::optional<std::size_t> ProgramTrack::locate(std::int64_t line, const gcode::AxisValues& joints,
                                                std::size_t from) const {
  const auto it = by_line_.find(line);
  if (it == by_line_.end()) return std::nullopt;
  const std::vector<std::size_t>& list = it->second;
  // The machine moves on through the program: the next group of this line at or
  // after the current motion, or the first one when it started again.
  auto first = std::lower_bound(list.begin(), list.end(), from);
  if (first == list.end()) first = list.begin();
  std::size_t best = *first;
  double best_d = chordDistance2(motions_[best].motion, joints);
  for (auto i = first + 1; i != list.end() && *i == *(i - 1) + 1; ++i) {
    const double d = chordDistance2(motions_[*i].motion, joints);
    if (d < best_d) best = *i, best_d = d;
  }
  return best;
}

const std::string& ProgramTrack::blockText(std::int64_t line) const {
  static const std::string kNone;
  if (line < 1 || line > static_cast<std::int64_t>(lines_.size())) return kNone;
  return lines_[static_cast<std::size_t>(line - 1)];
}

}  // namespace mdhd::shadow

#include "daemon/shadow_lookahead.h"

#include <cmath>

#include "sim/kinematics/joint_path.h"
#include "sim/kinematics/motion_time.h"

namespace mdhd::shadow {
namespace {

double distance2(const gcode::AxisValues& a, const gcode::AxisValues& b) {
  double d = 0.0;
  for (int i = 0; i < gcode::kAxisCount; ++i) d += (a[i] - b[i]) * (a[i] - b[i]);
  return d;
}

// The path parameter of the point of `path` closest to q (joint space): the best
// of 64 samples, refined by halving around it.
double closestParameter(const kin::JointPath& path, const gcode::AxisValues& q) {
  constexpr int kSamples = 64;
  double best = 0.0, best_d = distance2(path.at(0.0), q);
  for (int i = 1; i <= kSamples; ++i) {
    const double s = double(i) / kSamples;
    if (const double d = distance2(path.at(s), q); d < best_d) best = s, best_d = d;
  }
  for (double h = 0.5 / kSamples; h > 1e-9; h *= 0.5) {
    for (const double s : {best - h, best + h}) {
      if (s < 0.0 || s > 1.0) continue;
      if (const double d = distance2(path.at(s), q); d < best_d) best = s, best_d = d;
    }
  }
  return best;
}

}  // namespace

std::optional<gcode::Motion> restOfMotion(const TrackedMotion& m, const kin::Kinematics& kin,
                                          const gcode::AxisValues& joints) {
  const kin::JointPath path(kin, m.motion, m.tool_length);
  const double s = closestParameter(path, joints);
  if (s >= 1.0 - 1e-6) return std::nullopt;
  gcode::Motion rest = m.motion;
  rest.start = path.programAt(s);
  return rest;
}

std::size_t lookAhead(check::Simulation& ahead, const ProgramTrack& track,
                      const kin::Kinematics& kin, std::size_t index,
                      const gcode::AxisValues& joints, const LookaheadSpan& span,
                      const std::function<void(const PredictedContact&)>& found) {
  std::size_t simulated = 0;
  double elapsed = 0.0;  // machine time from the pose to the start of the motion
  std::size_t seen = ahead.collisions().size();
  try {
    for (std::size_t k = index; k < track.size() && k <= index + span.max_motions; ++k) {
      const TrackedMotion& t = track.at(k);
      gcode::Motion m = t.motion;
      double seconds = t.seconds;
      if (k == index) {
        const auto rest = restOfMotion(t, kin, joints);
        if (!rest) continue;
        m = *rest;
        seconds = kin::motionSeconds(m, kin, t.tool_length);
      } else {
        elapsed += t.pause_before;
      }
      m.block_text = &track.blockText(m.pos.line);
      ahead.motion(m);
      ++simulated;
      const std::vector<check::Collision>& all = ahead.collisions();
      for (; seen < all.size(); ++seen) found({all[seen], k, elapsed + all[seen].path_s * seconds});
      elapsed += seconds;
      if (k > index && elapsed >= span.seconds) break;
    }
  } catch (const gcode::GcodeError&) {
    // A motion the engine cannot simulate ends the look-ahead; the live carving
    // reports it when the machine gets there.
  } catch (const kin::KinematicsError&) {
  } catch (const kin::MotionTimeError&) {
  }
  return simulated;
}

}  // namespace mdhd::shadow

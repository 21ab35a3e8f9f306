#pragma once
// Look-ahead of a shadow that knows the program: from the machine's pose inside
// a program motion, the rest of that motion and the next ones are simulated on a
// fork of the live simulation (a copy of the stock), and every collision episode
// that begins there is a predicted contact, with the machine time until it.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "daemon/shadow_program.h"
#include "sim/check/simulation.h"

namespace mdhd::shadow {

struct LookaheadSpan {
  double seconds = 2.0;          // machine time to look ahead (at least the next motion)
  std::size_t max_motions = 32;  // and at most this many motions after the current one
};

struct PredictedContact {
  check::Collision collision;  // its line, block, tip, joints; depth within the span
  std::size_t motion = 0;      // index of the motion in the track
  double seconds = 0.0;        // machine time from the pose to the first contact
};

// The rest of tracked motion `m` from the machine's `joints` on: the motion with
// its start moved to the closest point of its path (as the program's own axis
// values, so arcs and tool-centre-point moves keep their shape). nullopt when
// the machine is at its end.
std::optional<gcode::Motion> restOfMotion(const TrackedMotion& m, const kin::Kinematics& kin,
                                          const gcode::AxisValues& joints);

// Runs `ahead` through the rest of motion `index` from `joints` and the motions
// after it within `span`, calling `found` for each contact as soon as the motion
// that makes it is simulated (a long look-ahead warns of the first contact
// early). Stops early at a motion the engine cannot simulate; check::Cancelled
// passes through. Returns the number of motions simulated.
std::size_t lookAhead(check::Simulation& ahead, const ProgramTrack& track,
                      const kin::Kinematics& kin, std::size_t index,
                      const gcode::AxisValues& joints, const LookaheadSpan& span,
                      const std::function<void(const PredictedContact&)>& found);

}  // namespace mdhd::shadow

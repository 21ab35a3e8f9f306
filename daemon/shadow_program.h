#pragma once
// The program a shadowed machine runs, interpreted once up front, so that the
// line the controller reports can be placed on a motion: for the kind of move
// (a rapid), the block text of alarms, and the look-ahead's next motions.
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "protocol/job.h"
#include "sim/gcode/motion.h"
#include "sim/kinematics/kinematics.h"

namespace mdhd::shadow {

struct TrackedMotion {
  gcode::Motion motion;       // block_text is null: see ProgramTrack::blockText
  double tool_length = 0.0;   // of motion.tool (0 without one)
  double seconds = 0.0;       // machine time (kin::motionSeconds)
  double pause_before = 0.0;  // dwells between the previous motion and this one
};

// Motions kept at most (about 250 bytes each); past them the rest of the program
// is not tracked (the look-ahead stops there, moves count as feeds).
inline constexpr std::size_t kMaxTrackedMotions = 250'000;

class ProgramTrack {
 public:
  // Interprets job.program (which must be set) without subroutine files: a
  // request never reaches the file system. Throws gcode::GcodeError (with the
  // line) when the program does not interpret or a move cannot be timed.
  ProgramTrack(const protocol::Job& job, const kin::Kinematics& kin);

  std::size_t size() const { return motions_.size(); }
  const TrackedMotion& at(std::size_t i) const { return motions_[i]; }
  bool truncated() const { return truncated_; }

  // The motion the machine is in when it reports `line` at `joints`: among the
  // motions of that line, the first group at or after `from` (else the first
  // group: the program started again), and within the group (a canned cycle
  // makes several) the one whose joint-space chord passes closest to `joints`.
  // nullopt when no tracked motion is on that line.
  std::optional<std::size_t> locate(std::int64_t line, const gcode::AxisValues& joints,
                                    std::size_t from) const;

  // Text of a line of the program (1-based), "" past its end.
  const std::string& blockText(std::int64_t line) const;

 private:
  std::vector<TrackedMotion> motions_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> by_line_;
  std::vector<std::string> lines_;
  bool truncated_ = false;
};

}  // namespace mdhd::shadow

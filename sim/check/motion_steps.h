#pragma once
// Where along a motion the tool is stepped. A JointPath is linear in joint space,
// not in W (a rotary table swings the tip along an arc), so a motion is cut into
// pieces until the tip at each piece's middle lies within the tolerance of the
// chord and the axis there within it of the great circle. Straight moves that
// turn no rotary joint are one piece: their sweep is exact.
#include <vector>

#include "sim/geometry/tool_pose.h"
#include "sim/kinematics/joint_path.h"

namespace mdhd::check {

struct StepPose {
  double s = 0.0;        // path parameter
  kin::JointValues q{};  // joints there
  geom::ToolPose pose;   // tool tip and axis in W
};

// Limits that keep one pathological motion from running away with time and memory.
inline constexpr int kMaxPiecesPerMotion = 1 << 14;
inline constexpr int kMaxSplitDepth = 14;
// Every piece of a rotary or arc motion turns by at most this much before refinement.
inline constexpr double kMaxPieceDegrees = 5.0;

// The poses at the piece ends, first s = 0, last s = 1. steps > 0: that many equal
// pieces in s. `reach`: distance of the tool's farthest point from the tip (it
// weighs the axis deviation). Throws kin::KinematicsError from the path.
std::vector<StepPose> stepPoses(const kin::JointPath& path, int steps, double tolerance,
                                double reach);

// The tool pose of a joint vector: kinematics' pose as geometry's type.
geom::ToolPose toolPoseAt(const kin::JointPath& path, const kin::JointValues& q);

}  // namespace mdhd::check

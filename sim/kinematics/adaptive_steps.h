#pragma once
// How finely to step a JointPath so that the simulator's chain of straight tool
// moves stays within a chordal tolerance of the true, curved motion in W
// (options.steps = 0 in the job format).
#include "sim/kinematics/joint_path.h"

namespace mdhd::kin {

// The number n >= 1 of equal steps in s such that every point of the tool within
// `reach` of its tip (holder included: reach = the farthest tool point from the tip)
// stays within `tolerance` of the straight segment between its positions at
// consecutive steps: a pure translation in W gives 1. Estimated from a dense sampling
// of the path (second differences of the tip and of the tool's rotation), capped at
// `max_steps`. Throws KinematicsError for a tolerance that is not > 0 or a reach < 0,
// and (tcp) when the path passes a singular pose.
int adaptiveSteps(const JointPath& path, double reach, double tolerance, int max_steps = 1 << 16);

}  // namespace mdhd::kin

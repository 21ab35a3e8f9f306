#include "sim/check/motion_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "sim/geometry/pose_interpolation.h"

namespace mdhd::check {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr gcode::Axis kRotary[] = {gcode::kA, gcode::kB, gcode::kC};

StepPose poseAt(const kin::JointPath& path, double s) {
  StepPose p;
  p.s = s;
  p.q = path.at(s);
  p.pose = toolPoseAt(path, p.q);
  return p;
}

double rotaryTravel(const kin::JointPath& path) {
  double most = 0.0;
  for (gcode::Axis a : kRotary) {
    if (!path.kinematics().hasAxis(a)) continue;
    most = std::max(most, std::abs(path.endJoints()[a] - path.startJoints()[a]));
  }
  return most;
}

// How far the middle pose strays from the piece's straight-and-slerped stand-in.
double deviation(const StepPose& a, const StepPose& m, const StepPose& b, double reach) {
  const glm::dvec3 chordMid = 0.5 * (a.pose.tip + b.pose.tip);
  double err = glm::length(m.pose.tip - chordMid);
  if (geom::axisAngle(a.pose.axis, b.pose.axis) < kPi * 0.999) {
    const geom::ToolPose slerped = geom::interpolatePose(a.pose, b.pose, 0.5);
    err += reach * geom::axisAngle(slerped.axis, m.pose.axis);
  } else {
    err = INFINITY;  // opposite axes: no great circle, must split
  }
  return err;
}

struct Refiner {
  const kin::JointPath& path;
  double tolerance;
  double reach;
  std::vector<StepPose>& out;
  bool outOfPieces = false;  // a piece strayed further than the tolerance at the budget

  // Appends the poses after `a` up to and including `b`.
  void refine(const StepPose& a, const StepPose& b, int depth) {
    if (depth < kMaxSplitDepth) {
      const StepPose m = poseAt(path, 0.5 * (a.s + b.s));
      if (deviation(a, m, b, reach) > tolerance) {
        if (static_cast<int>(out.size()) < kMaxPiecesPerMotion) {
          refine(a, m, depth + 1);
          refine(m, b, depth + 1);
          return;
        }
        outOfPieces = true;
      }
    }
    out.push_back(b);
  }
};

}  // namespace

geom::ToolPose toolPoseAt(const kin::JointPath& path, const kin::JointValues& q) {
  const kin::ToolPose p = path.kinematics().toolPose(q, path.toolLength());
  return geom::ToolPose{p.tip, p.axis};
}

std::vector<StepPose> stepPoses(const kin::JointPath& path, int steps, double tolerance,
                                double reach) {
  std::vector<StepPose> out;
  out.push_back(poseAt(path, 0.0));
  if (steps > 0) {
    for (int i = 1; i <= steps; ++i) out.push_back(poseAt(path, double(i) / steps));
    return out;
  }
  const double turn = rotaryTravel(path);
  const double arcDegrees = path.isArc() ? std::abs(path.arcSweep()) * 180.0 / kPi : 0.0;
  if (turn == 0.0 && !path.isArc()) {
    out.push_back(poseAt(path, 1.0));
    return out;
  }
  const double degrees = std::max(turn, arcDegrees);
  const double wanted = std::ceil(degrees / kMaxPieceDegrees);
  const int initial = static_cast<int>(std::clamp(wanted, 1.0, kMaxPiecesPerMotion / 4.0));
  Refiner refiner{path, tolerance, reach, out};
  for (int i = 1; i <= initial; ++i) {
    const StepPose a = out.back();
    refiner.refine(a, poseAt(path, double(i) / initial), 0);
  }
  // Beyond the budget the last pieces would be chords far outside the tolerance (a
  // 1,000,000 degree turn of C removed 44 % too much): refuse rather than guess.
  if (refiner.outOfPieces || wanted > initial) {
    char text[300];
    std::snprintf(text, sizeof text,
                  "the move turns %.0f degrees; within the tolerance of %g mm it needs more "
                  "than %d steps: split it into shorter moves",
                  degrees, tolerance, kMaxPiecesPerMotion);
    throw std::invalid_argument(text);
  }
  return out;
}

}  // namespace mdhd::check

#include "sim/kinematics/adaptive_steps.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mdhd::kin {
namespace {

constexpr int kMinSamples = 16;
constexpr double kSampleDegrees = 1.0;
constexpr int kMaxSamples = 1 << 16;

double frobenius(const glm::dmat3& m) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) sum += glm::dot(m[c], m[c]);
  return std::sqrt(sum);
}

// How much the path turns anything: degrees of arc or of any rotary joint.
double turningDegrees(const JointPath& path) {
  double degrees = path.isArc() ? std::abs(path.arcSweep()) * 180.0 / std::numbers::pi : 0.0;
  const JointValues& a = path.startJoints();
  const JointValues& b = path.endJoints();
  for (int r : {gcode::kA, gcode::kB, gcode::kC})
    degrees = std::max(degrees, std::abs(b[r] - a[r]));
  return degrees;
}

}  // namespace

int adaptiveSteps(const JointPath& path, double reach, double tolerance, int max_steps) {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw KinematicsError("adaptive steps need a tolerance > 0");
  }
  if (!(reach >= 0.0) || !std::isfinite(reach)) {
    throw KinematicsError("adaptive steps need a tool reach >= 0");
  }
  const Kinematics& kin = path.kinematics();
  const double length = path.toolLength();
  const int m = std::clamp(static_cast<int>(std::ceil(turningDegrees(path) / kSampleDegrees)),
                           kMinSamples, kMaxSamples);
  const double h = 1.0 / m;
  // A tool point p(s) = tip(s) + Q(s) v with |v| <= reach has |p''| <= |tip''| + reach |Q''|;
  // a chord over ds deviates from the curve by at most max|p''| ds^2 / 8.
  Rigid prev2;
  Rigid prev1;
  glm::dvec3 tip2{0.0};
  glm::dvec3 tip1{0.0};
  double curvature = 0.0;
  const glm::dvec3 tipInTool = -length * kin.spindleAxis();
  for (int i = 0; i <= m; ++i) {
    const Rigid t = kin.toolInWorkpiece(path.at(i * h));
    const glm::dvec3 tip = t.point(tipInTool);
    if (i >= 2) {
      const double a = glm::length(tip - 2.0 * tip1 + tip2) / (h * h);
      const double r = frobenius(t.rotation - 2.0 * prev1.rotation + prev2.rotation) / (h * h);
      curvature = std::max(curvature, a + reach * r);
    }
    prev2 = prev1, prev1 = t;
    tip2 = tip1, tip1 = tip;
  }
  // Rounding in the second differences is ~1e-16 |p| / h^2: below that it is a line.
  if (curvature * h * h <= 1e-12 * (1.0 + glm::length(tip1) + reach)) return 1;
  const double steps = std::ceil(std::sqrt(curvature / (8.0 * tolerance)));
  return static_cast<int>(std::clamp(steps, 1.0, static_cast<double>(max_steps)));
}

}  // namespace mdhd::kin

#include "sim/kinematics/limits.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace mdhd::kin {
namespace {

constexpr int kMinSteps = 32;
constexpr double kStepDegrees = 2.0;
constexpr int kMaxSteps = 200000;
constexpr int kRefineIterations = 64;  // 0.618^64 ~ 1e-13 of a sample interval

struct Point {
  double s = 0.0;
  double v = 0.0;
};

// Violation of one joint's range by the value v, or 0 when inside: +1 above, -1 below.
int side(const Limits& l, double v) {
  if (std::isnan(v)) return 1;  // never inside: a NaN must not pass as in range
  if (v > l.max + kLimitSlack) return 1;
  if (v < l.min - kLimitSlack) return -1;
  return 0;
}

LimitViolation make(int joint, gcode::Axis axis, const Limits& l, int dir, double v) {
  LimitViolation out;
  out.joint = joint;
  out.axis = axis;
  out.limit = dir > 0 ? l.max : l.min;
  out.value = v;
  out.excess = std::abs(v - out.limit);
  out.side = dir;
  return out;
}

// A joint that moves linearly from a to b: exact. One entry per side it is beyond:
// two when it goes from below its min to beyond its max (or back) in one move.
void linearCheck(int joint, gcode::Axis axis, const Limits& l, double a, double b,
                 std::vector<LimitViolation>& out) {
  const int dirA = side(l, a);
  const int dirB = side(l, b);
  for (const int dir : {dirA, dirB != dirA ? dirB : 0}) {
    if (dir == 0) continue;
    // The worst is the end farther out on that side.
    const bool endWorse = dir > 0 ? b > a : b < a;
    LimitViolation v = make(joint, axis, l, dir, endWorse ? b : a);
    v.worst_s = endWorse ? 1.0 : 0.0;
    v.first_s = dirA == dir ? 0.0 : std::clamp((v.limit - a) / (b - a), 0.0, 1.0);
    out.push_back(v);
  }
}

// Golden-section search for the maximum of f on [a, b] (assumed unimodal there).
Point goldenMax(const std::function<double(double)>& f, double a, double b) {
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = b - g * (b - a);
  double x2 = a + g * (b - a);
  double f1 = f(x1);
  double f2 = f(x2);
  for (int i = 0; i < kRefineIterations && b - a > 1e-15; ++i) {
    if (f1 < f2) {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
    } else {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
    }
  }
  return f1 < f2 ? Point{x2, f2} : Point{x1, f1};
}

// The s values to sample a non-linear path at, sorted.
std::vector<double> sampleParameters(const JointPath& path) {
  double degrees = 0.0;
  if (path.isArc()) degrees = std::abs(path.arcSweep()) * 180.0 / std::numbers::pi;
  if (path.tcp()) {
    const JointValues& a = path.startJoints();
    const JointValues& b = path.endJoints();
    for (int r : {gcode::kA, gcode::kB, gcode::kC})
      degrees = std::max(degrees, std::abs(b[r] - a[r]));
  }
  const int n =
      std::clamp(static_cast<int>(std::ceil(degrees / kStepDegrees)), kMinSteps, kMaxSteps);
  std::vector<double> s;
  s.reserve(static_cast<std::size_t>(n) + 8);
  for (int i = 0; i <= n; ++i) s.push_back(static_cast<double>(i) / n);
  if (path.isArc() && path.arcSweep() != 0.0) {
    // Where the arc's coordinates peak: at the quarter angles (exact for a constant radius).
    const double quarter = std::numbers::pi / 2.0;
    const double a0 = path.arcStartAngle();
    const double a1 = a0 + path.arcSweep();
    const double lo = std::min(a0, a1);
    const double hi = std::max(a0, a1);
    const int count = std::min(
        kMaxSteps, static_cast<int>(std::floor(hi / quarter) - std::ceil(lo / quarter)) + 1);
    const double k0 = std::ceil(lo / quarter);
    for (int k = 0; k < count; ++k) s.push_back(((k0 + k) * quarter - a0) / path.arcSweep());
  }
  std::sort(s.begin(), s.end());
  return s;
}

// One joint, sampled: refine every local extreme, then for each side find the first
// point beyond it and the farthest one (one entry per side, the side reached first first).
void sampledCheck(const JointPath& path, int joint, gcode::Axis axis, const Limits& l,
                  const std::vector<double>& s, const std::vector<double>& v,
                  std::vector<LimitViolation>& out) {
  const auto f = [&](double t) { return path.at(t)[axis]; };
  std::vector<Point> pts;
  pts.reserve(s.size() + 16);
  for (std::size_t i = 0; i < s.size(); ++i) pts.push_back({s[i], v[i]});
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double prev = i > 0 ? v[i - 1] : v[i];
    const double next = i + 1 < n ? v[i + 1] : v[i];
    const double a = s[i > 0 ? i - 1 : i];
    const double b = s[i + 1 < n ? i + 1 : i];
    if (b <= a) continue;
    // Between dense samples a smooth joint overshoots its best sample by well under the
    // step to its neighbours (a quarter of it for a parabola): extremes farther than
    // twice that from a limit cannot reach it and are not refined.
    const double margin = 2.0 * std::max(std::abs(v[i] - prev), std::abs(v[i] - next));
    // Strict on one side so that plateaus (a joint that does not move) cost nothing.
    if (v[i] >= prev && v[i] >= next && (v[i] > prev || v[i] > next)) {
      if (v[i] + margin >= l.max) pts.push_back(goldenMax(f, a, b));
    } else if (v[i] <= prev && v[i] <= next && (v[i] < prev || v[i] < next)) {
      if (v[i] - margin > l.min) continue;
      Point p = goldenMax([&](double t) { return -f(t); }, a, b);
      pts.push_back({p.s, -p.v});
    }
  }
  std::sort(pts.begin(), pts.end(), [](const Point& x, const Point& y) { return x.s < y.s; });
  std::vector<LimitViolation> sides;
  for (const int dir : {1, -1}) {
    std::size_t k = 0;
    while (k < pts.size() && side(l, pts[k].v) != dir) ++k;
    if (k == pts.size()) continue;
    LimitViolation o = make(joint, axis, l, dir, pts[k].v);
    o.worst_s = pts[k].s;
    for (const Point& p : pts) {
      if (side(l, p.v) == dir && dir * (p.v - o.value) > 0) o.value = p.v, o.worst_s = p.s;
    }
    o.excess = std::abs(o.value - o.limit);
    if (k > 0) {
      // Bisect for the crossing between the last point not beyond this side and the first
      // beyond it.
      double lo = pts[k - 1].s;
      double hi = pts[k].s;
      for (int i = 0; i < kRefineIterations && hi - lo > 1e-15; ++i) {
        const double mid = 0.5 * (lo + hi);
        (side(l, f(mid)) == dir ? hi : lo) = mid;
      }
      o.first_s = hi;
    }
    sides.push_back(o);
  }
  if (sides.size() == 2 && sides[1].first_s < sides[0].first_s) std::swap(sides[0], sides[1]);
  out.insert(out.end(), sides.begin(), sides.end());
}

}  // namespace

std::optional<LimitViolation> checkLimits(const Kinematics& kin, const JointValues& q) {
  const Machine& m = kin.machine();
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    if (!m.joints[j].limits) continue;
    const auto axis = *axisOfName(m.joints[j].name);
    const Limits& l = *m.joints[j].limits;
    if (const int dir = side(l, q[axis])) return make(static_cast<int>(j), axis, l, dir, q[axis]);
  }
  return std::nullopt;
}

std::vector<LimitViolation> checkLimitsAll(const JointPath& path) {
  const Machine& m = path.kinematics().machine();
  std::vector<double> s;  // sample parameters, made on first need
  std::vector<JointValues> q;
  std::vector<LimitViolation> out;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    if (!m.joints[j].limits) continue;
    const auto axis = *axisOfName(m.joints[j].name);
    const Limits& l = *m.joints[j].limits;
    const bool solved = path.tcp() && axis <= gcode::kZ;
    const bool onArc = path.isArc() && (axis == path.arcFirst() || axis == path.arcSecond());
    const std::size_t first = out.size();
    if (!solved && !onArc) {
      linearCheck(static_cast<int>(j), axis, l, path.startJoints()[axis], path.endJoints()[axis],
                  out);
    } else {
      if (s.empty()) {
        s = sampleParameters(path);
        q.reserve(s.size());
        for (double t : s) q.push_back(path.at(t));
      }
      std::vector<double> values(s.size());
      for (std::size_t i = 0; i < s.size(); ++i) values[i] = q[i][axis];
      sampledCheck(path, static_cast<int>(j), axis, l, s, values, out);
    }
    // Still beyond that same side at the end: a joint that crossed to the other side
    // has left the first one.
    const int endSide = side(l, path.endJoints()[axis]);
    for (std::size_t i = first; i < out.size(); ++i) out[i].outside_at_end = endSide == out[i].side;
  }
  // Machine order (then the side reached first) within equal first_s: the sort is stable.
  std::stable_sort(out.begin(), out.end(), [](const LimitViolation& a, const LimitViolation& b) {
    return a.first_s < b.first_s;
  });
  return out;
}

std::optional<LimitViolation> checkLimits(const JointPath& path) {
  std::vector<LimitViolation> all = checkLimitsAll(path);
  if (all.empty()) return std::nullopt;
  return all.front();
}

}  // namespace mdhd::kin

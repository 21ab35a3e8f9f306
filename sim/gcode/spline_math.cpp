#include "sim/gcode/spline_math.h"

#include <algorithm>
#include <cmath>

namespace mdhd::gcode {

NurbsCurve::NurbsCurve(std::vector<ControlPoint> points, int order)
    : points_(std::move(points)), order_(order) {
  const int n = static_cast<int>(points_.size()) - 1;
  const int k = order_;
  knots_.reserve(static_cast<std::size_t>(n + k + 1));
  for (int i = 0; i <= n + k; ++i) knots_.push_back(i < k ? 0.0 : (i <= n ? i - k + 1 : n - k + 2));
  u_max_ = n - k + 2;
  work_.resize(static_cast<std::size_t>(k));
}

PlanePoint NurbsCurve::at(double u) const {
  const int n = static_cast<int>(points_.size()) - 1;
  const int p = order_ - 1;  // degree
  u = std::clamp(u, 0.0, u_max_);
  // Knot span s with knots_[s] <= u < knots_[s + 1] (the last span at u_max).
  const int s = std::min(p + static_cast<int>(std::floor(u)), n);
  for (int j = 0; j <= p; ++j) {
    const ControlPoint& c = points_[static_cast<std::size_t>(j + s - p)];
    work_[static_cast<std::size_t>(j)] = {c.x * c.w, c.y * c.w, c.w};
  }
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const double lo = knots_[static_cast<std::size_t>(j + s - p)];
      const double hi = knots_[static_cast<std::size_t>(j + 1 + s - r)];
      const double alpha = hi > lo ? (u - lo) / (hi - lo) : 0.0;
      auto& d = work_[static_cast<std::size_t>(j)];
      const auto& e = work_[static_cast<std::size_t>(j - 1)];
      for (int c = 0; c < 3; ++c) d[c] = (1.0 - alpha) * e[c] + alpha * d[c];
    }
  }
  const auto& h = work_[static_cast<std::size_t>(p)];
  return {h[0] / h[2], h[1] / h[2]};
}

namespace {

// Distance from q to the segment a-b.
double segmentDistance(const PlanePoint& q, const PlanePoint& a, const PlanePoint& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(q[0] - (a[0] + t * dx), q[1] - (a[1] + t * dy));
}

}  // namespace

void flattenCurve(const NurbsCurve& curve, const PlanePoint& last_control, double tolerance,
                  std::vector<PlanePoint>& out, std::size_t max_points) {
  // Each knot span is one rational polynomial piece; it is split at least in
  // four so that an S-shaped piece (zero deviation at its middle) is caught,
  // then halved while a quarter, middle or three-quarter point lies farther
  // than the tolerance from the chord.
  struct Piece {
    double u0, u1;
    PlanePoint p0, p1;
    int depth;
  };
  constexpr int kMaxDepth = 40;
  constexpr int kMinSplit = 4;
  const std::size_t first = out.size();
  std::vector<Piece> stack;
  const int spans = static_cast<int>(std::lround(curve.uMax()));
  for (int span = 0; span < spans; ++span) {
    PlanePoint prev = curve.at(span);
    for (int part = 0; part < kMinSplit; ++part) {
      const double u0 = span + static_cast<double>(part) / kMinSplit;
      const double u1 = span + static_cast<double>(part + 1) / kMinSplit;
      const PlanePoint p1 = curve.at(u1);
      stack.push_back({u0, u1, prev, p1, 0});
      prev = p1;
      while (!stack.empty()) {
        const Piece piece = stack.back();
        stack.pop_back();
        const double du = piece.u1 - piece.u0;
        double deviation = 0.0;
        for (double f : {0.25, 0.5, 0.75})
          deviation =
              std::max(deviation, segmentDistance(curve.at(piece.u0 + f * du), piece.p0, piece.p1));
        const bool budget_left = out.size() - first + stack.size() + 2 < max_points;
        if (deviation > tolerance && piece.depth < kMaxDepth && budget_left) {
          const double um = piece.u0 + 0.5 * du;
          const PlanePoint pm = curve.at(um);
          // Right half below the left so that the left one is emitted first.
          stack.push_back({um, piece.u1, pm, piece.p1, piece.depth + 1});
          stack.push_back({piece.u0, um, piece.p0, pm, piece.depth + 1});
          continue;
        }
        out.push_back(piece.p1);
      }
    }
  }
  // The clamped curve ends at its last control point; take it exactly.
  if (out.size() > first)
    out.back() = last_control;
  else
    out.push_back(last_control);
}

}  // namespace mdhd::gcode

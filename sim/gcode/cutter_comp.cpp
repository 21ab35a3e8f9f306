// Cutter radius compensation (G41/G42) as LinuxCNC 2.9 does it: one move is
// held back until the next one shows whether the corner between them is
// convex (an arc is inserted around it) or concave (the held move is shortened
// to where the tool touches both). Held moves are released, with the line of
// the block being executed, when the next move settles their end point.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sim/gcode/arc_math.h"
#include "sim/gcode/block_step.h"

namespace mdhd::gcode {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSmall = 0.05;  // TOLERANCE_CONCAVE_CORNER, radians

bool toolInsideArc(CompSide side, int turn) {
  return (side == CompSide::kLeft && turn > 0) || (side == CompSide::kRight && turn < 0);
}

AxisValues withXY(AxisValues v, double x, double y) {
  v[kX] = x;
  v[kY] = y;
  return v;
}

}  // namespace

void BlockExecutor::setEndpoint(double x, double y) {
  endpoint_[0] = x;
  endpoint_[1] = y;
  endpoint_valid_ = true;
}

void BlockExecutor::enqueueStraight(Step&, MotionType type, double dx, double dy,
                                    const AxisValues& end, const FeedInfo& f) {
  Queued q;
  q.kind = Queued::kStraight;
  q.type = type;
  q.dx = dx;
  q.dy = dy;
  q.end = end;
  q.feed = f;
  queue_.push_back(q);
}

void BlockExecutor::enqueueArc(Step&, double original_turns, const AxisValues& end, double c1,
                               double c2, int turn, const FeedInfo& f) {
  Queued q;
  q.kind = Queued::kArc;
  q.type = MotionType::kArc;
  q.original_turns = original_turns;
  q.end = end;
  q.c1 = c1;
  q.c2 = c2;
  q.turn = turn;
  q.feed = f;
  queue_.push_back(q);
}

void BlockExecutor::flushQueue(Step& st) {
  endpoint_valid_ = false;
  for (const Queued& q : queue_) {
    switch (q.kind) {
      case Queued::kStraight:
        out_.straight(q.type, q.end, st.s, st.block, q.feed, true);
        break;
      case Queued::kArc:
        out_.arc(q.end, q.c1, q.c2, q.turn, st.s, st.block, q.feed, true);
        break;
      case Queued::kEvent: {
        Event e = q.event;
        e.pos = st.block.pos;
        out_.event(e);
        break;
      }
    }
  }
  queue_.clear();
}

void BlockExecutor::moveEndpointAndFlush(Step& st, double x, double y) {
  if (queue_.empty()) return;
  const double unit = st.unit();
  for (Queued& q : queue_) {
    if (q.kind == Queued::kArc) {
      const double r1 = std::hypot(q.end[kX] - q.c1, q.end[kY] - q.c2);
      const double r2 = std::hypot(x - q.c1, y - q.c2);
      const double l2 = findTurn(endpoint_[0], endpoint_[1], q.c1, q.c2, q.turn, x, y);
      if (std::fabs(r1 - r2) > 0.01 * unit) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "BUG: cutter compensation has generated an invalid arc with mismatched "
                      "radii r1 %f r2 %f",
                      r1 / unit, r2 / unit);
        st.fail(text);
      }
      if (q.original_turns != 0.0 && endpoint_valid_ &&
          std::fabs(l2) > std::fabs(q.original_turns) + 0.001)
        st.fail("Arc move in concave corner cannot be reached by the tool without gouging");
    } else if (q.kind == Queued::kStraight) {
      const double dot = q.dx * (x - endpoint_[0]) + q.dy * (y - endpoint_[1]);
      if (endpoint_valid_ && dot < 0)
        st.fail(q.type == MotionType::kRapid
                    ? "Straight traverse in concave corner cannot be reached by the tool without "
                      "gouging"
                    : "Straight feed in concave corner cannot be reached by the tool without "
                      "gouging");
    } else {
      continue;
    }
    q.end[kX] = x;
    q.end[kY] = y;
  }
  flushQueue(st);
  setEndpoint(x, y);
}

void BlockExecutor::compStraightFirst(Step& st, MotionType type, const AxisValues& end,
                                      const FeedInfo& f) {
  InterpState& s = st.s;
  const double radius = s.comp_radius;
  const double cx = s.current[kX], cy = s.current[kY];
  const double px = end[kX], py = end[kY];
  if (std::hypot(px - cx, py - cy) <= radius)
    st.fail("Length of cutter compensation entry move is not greater than the tool radius");
  const double alpha =
      std::atan2(py - cy, px - cx) + (s.comp_side == CompSide::kLeft ? kPi / 2 : -kPi / 2);
  const double ex = px + radius * std::cos(alpha), ey = py + radius * std::sin(alpha);
  setEndpoint(cx, cy);
  const AxisValues tool_end = withXY(end, ex, ey);
  enqueueStraight(st, type, std::cos(alpha), std::sin(alpha), tool_end, f);
  s.comp_first_move = false;
  s.current = tool_end;
  s.programmed = end;
}

void BlockExecutor::compStraight(Step& st, MotionType type, const AxisValues& end,
                                 const FeedInfo& f) {
  InterpState& s = st.s;
  const double cx = s.current[kX], cy = s.current[kY], cz = s.current[kZ];
  const double opx = s.programmed[kX], opy = s.programmed[kY];
  const double px = end[kX], py = end[kY];
  AxisValues tool_end = withXY(end, cx, cy);
  if (px == opx && py == opy) {  // no XY motion: the tool keeps its offset
    enqueueStraight(st, type, 0.0, 0.0, tool_end, f);
  } else {
    const bool left = s.comp_side == CompSide::kLeft;
    const double radius = s.comp_radius;
    double theta = std::atan2(cy - opy, cx - opx);
    double alpha = std::atan2(py - opy, px - opx);
    double beta, gamma;
    if (left) {
      if (theta < alpha) theta += 2 * kPi;
      beta = (theta - alpha) - kPi / 2;
      gamma = kPi / 2;
    } else {
      if (alpha < theta) alpha += 2 * kPi;
      beta = (alpha - theta) - kPi / 2;
      gamma = -kPi / 2;
    }
    const double ex = px + radius * std::cos(alpha + gamma);
    const double ey = py + radius * std::sin(alpha + gamma);
    double mid_x = opx + radius * std::cos(alpha + gamma);
    double mid_y = opy + radius * std::sin(alpha + gamma);
    const bool front_is_arc = !queue_.empty() && queue_.front().kind == Queued::kArc;
    bool concave;
    if (beta < -kSmall || beta > kPi + kSmall) {
      concave = true;
    } else if (beta > kPi - kSmall && front_is_arc &&
               ((!left && queue_.front().turn > 0) || (left && queue_.front().turn < 0))) {
      concave = true;  // the "h" shape: stay on the outside of the round part
    } else {
      concave = false;
    }
    if (!concave && beta > kSmall) {  // convex corner: an arc around the programmed point
      moveEndpointAndFlush(st, cx, cy);
      AxisValues corner = withXY(end, mid_x, mid_y);
      corner[kZ] = cz;
      if (type == MotionType::kFeed)
        enqueueArc(st, 0.0, corner, opx, opy, left ? -1 : 1, f);
      else
        enqueueStraight(st, MotionType::kRapid, 0.0, 0.0, corner, f);
      flushQueue(st);
      setEndpoint(mid_x, mid_y);
    } else if (concave) {
      if (!front_is_arc) {  // line -> line: back up along the previous move
        const double halfcorner = (beta + kPi) / 2.0;
        if (halfcorner == 0.0)
          st.fail("Zero degree inside corner is invalid for cutter compensation");
        const double retreat = radius / std::tan(halfcorner);
        mid_x = cx + retreat * std::cos(theta + gamma);
        mid_y = cy + retreat * std::sin(theta + gamma);
        moveEndpointAndFlush(st, mid_x, mid_y);
      } else {  // arc -> line: where the offset line meets the offset arc
        const Queued& prev = queue_.front();
        const double oldrad = std::hypot(prev.c2 - prev.end[kY], prev.c1 - prev.end[kX]);
        const double base_dir = std::atan2(py - opy, px - opx);
        const double th = prev.turn > 0 ? base_dir + kPi / 2 : base_dir - kPi / 2;
        const double phi = std::atan2(prev.c2 - opy, prev.c1 - opx);
        const bool inside = toolInsideArc(s.comp_side, prev.turn);
        const double oldrad_uncomp = inside ? oldrad + radius : oldrad - radius;
        const double d = oldrad_uncomp * std::cos(th - phi);
        const double l = (inside ? d - radius : d + radius) / oldrad;
        if (l > 1.0 || l < -1.0)
          st.fail(
              "Arc to straight motion makes a corner the compensated tool can't fit in "
              "without gouging");
        const double sign = (inside == (prev.turn > 0)) ? -1.0 : 1.0;
        const double angle = sign * std::acos(l) + th + kPi;
        mid_x = prev.c1 + oldrad * std::cos(angle);
        mid_y = prev.c2 + oldrad * std::sin(angle);
        moveEndpointAndFlush(st, mid_x, mid_y);
      }
    } else {  // straight on, or tangent arc -> line
      flushQueue(st);
      setEndpoint(cx, cy);
    }
    tool_end = withXY(end, ex, ey);
    enqueueStraight(st, type, px - opx, py - opy, tool_end, f);
  }
  s.current = tool_end;
  s.programmed = end;
}

void BlockExecutor::compArcFirst(Step& st, const AxisValues& end, const FeedInfo& f,
                                 const ArcFit& fit) {
  InterpState& s = st.s;
  const double radius = s.comp_radius;
  const double cx = s.current[kX], cy = s.current[kY];
  double ex = end[kX], ey = end[kY];
  if (std::hypot(ex - cx, ey - cy) <= radius)
    st.fail("Radius of cutter compensation entry arc is not greater than the tool radius");
  const bool inside = toolInsideArc(s.comp_side, fit.turn);
  const double arc_radius = std::hypot(fit.center1 - cx, fit.center2 - cy);
  if (inside && arc_radius <= radius) st.fail("Tool radius not less than arc radius with comp");
  const double gamma = inside ? std::atan2(fit.center2 - ey, fit.center1 - ex)
                              : std::atan2(ey - fit.center2, ex - fit.center1);
  ex += radius * std::cos(gamma);
  ey += radius * std::sin(gamma);
  // New centre: on the line from the new end towards the old centre, equidistant
  // from the new end and the current point.
  const double b_len = std::hypot(cy - ey, cx - ex) / 2.0;
  const double ab_ang = std::atan2(fit.center2 - ey, fit.center1 - ex);
  const double a_ang = std::atan2(cy - ey, cx - ex) - ab_ang;
  if (std::fabs(std::cos(a_ang)) < 1e-6) st.fail("Tool radius not less than arc radius with comp");
  const double c_len = b_len / std::cos(a_ang);
  const double ncx = ex + c_len * std::cos(ab_ang), ncy = ey + c_len * std::sin(ab_ang);
  if (std::fabs(std::hypot(ncx - ex, ncy - ey) - std::hypot(ncx - cx, ncy - cy)) >
      arcTolerance(s.inch).spiral_abs)
    st.fail("Bug in tool radius comp");
  const AxisValues tool_end = withXY(end, ex, ey);
  enqueueArc(st, findTurn(cx, cy, ncx, ncy, fit.turn, ex, ey), tool_end, ncx, ncy, fit.turn, f);
  s.comp_first_move = false;
  s.current = tool_end;
  s.programmed = end;
}

void BlockExecutor::compArc(Step& st, const AxisValues& end, const FeedInfo& f, const ArcFit& fit) {
  InterpState& s = st.s;
  const bool left = s.comp_side == CompSide::kLeft;
  const double tool_radius = s.comp_radius;
  const double cx = s.current[kX], cy = s.current[kY], cz = s.current[kZ];
  const double opx = s.programmed[kX], opy = s.programmed[kY];
  const double end_x = end[kX], end_y = end[kY];
  const double centerx = fit.center1, centery = fit.center2;
  const int turn = fit.turn;
  const double arc_radius = std::hypot(centerx - end_x, centery - end_y);
  double theta = std::atan2(cy - opy, cx - opx);
  theta = left ? theta - kPi / 2 : theta + kPi / 2;
  double delta = std::atan2(centery - opy, centerx - opx);
  const double alpha = turn > 0 ? delta - kPi / 2 : delta + kPi / 2;
  double beta = left ? theta - alpha : alpha - theta;
  if (beta > 1.5 * kPi)
    beta -= 2 * kPi;
  else if (beta < -kPi / 2)
    beta += 2 * kPi;
  const bool inside = toolInsideArc(s.comp_side, turn);
  double gamma;
  if (inside) {
    gamma = std::atan2(centery - end_y, centerx - end_x);
    if (arc_radius <= tool_radius) st.fail("Tool radius not less than arc radius with comp");
  } else {
    gamma = std::atan2(end_y - centery, end_x - centerx);
    delta += kPi;
  }
  const double new_end_x = end_x + tool_radius * std::cos(gamma);
  const double new_end_y = end_y + tool_radius * std::sin(gamma);
  const AxisValues tool_end = withXY(end, new_end_x, new_end_y);
  const double sweep = findTurn(opx, opy, centerx, centery, turn, end_x, end_y);
  const bool front_is_arc = !queue_.empty() && queue_.front().kind == Queued::kArc;
  if (beta < -kSmall || beta > kPi + kSmall || (std::fabs(beta - kPi) < kSmall && !inside)) {
    // concave corner
    double midx, midy;
    if (!front_is_arc) {  // line -> arc
      const double ry = arc_radius * std::sin(beta - kPi / 2);
      double dist, angle;
      if (inside) {
        dist = arc_radius - tool_radius;
        const double l = (ry + tool_radius) / dist;
        if (l > 1.0 || l < -1.0)
          st.fail("Arc move in concave corner cannot be reached by the tool without gouging");
        angle = turn > 0 ? theta + std::asin(l) : theta - std::asin(l);
      } else {
        dist = arc_radius + tool_radius;
        const double l = (ry - tool_radius) / dist;
        if (l > 1.0 || l < -1.0)
          st.fail("Arc move in concave corner cannot be reached by the tool without gouging");
        angle = turn > 0 ? theta + kPi - std::asin(l) : theta + kPi + std::asin(l);
      }
      midx = centerx + dist * std::cos(angle);
      midy = centery + dist * std::sin(angle);
    } else {  // arc -> arc
      const Queued& prev = queue_.front();
      const double oldrad = std::hypot(prev.c2 - prev.end[kY], prev.c1 - prev.end[kX]);
      const double newrad = inside ? arc_radius - tool_radius : arc_radius + tool_radius;
      const double arc_cc = std::hypot(prev.c2 - centery, prev.c1 - centerx);
      if (oldrad == 0 || arc_cc == 0)
        st.fail("Arc to arc motion is invalid because the arcs have the same center");
      const double a =
          (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad) / (2 * oldrad * arc_cc);
      if (a > 1.0 || a < -1.0)
        st.fail(
            "Arc to arc motion makes a corner the compensated tool can't fit in without "
            "gouging");
      const double pullback = std::acos(a);
      const double cc_dir = std::atan2(centery - prev.c2, centerx - prev.c1);
      double dir;
      if (toolInsideArc(s.comp_side, prev.turn))
        dir = turn > 0 ? cc_dir + pullback : cc_dir - pullback;
      else
        dir = turn > 0 ? cc_dir - pullback : cc_dir + pullback;
      midx = prev.c1 + oldrad * std::cos(dir);
      midy = prev.c2 + oldrad * std::sin(dir);
    }
    moveEndpointAndFlush(st, midx, midy);
    enqueueArc(st, sweep, tool_end, centerx, centery, turn, f);
  } else if (beta > kSmall) {  // convex: an arc around the corner, then the arc
    const double midx = opx + tool_radius * std::cos(delta);
    const double midy = opy + tool_radius * std::sin(delta);
    flushQueue(st);
    AxisValues corner = withXY(end, midx, midy);
    corner[kZ] = cz;
    enqueueArc(st, 0.0, corner, opx, opy, left ? -1 : 1, f);
    flushQueue(st);
    setEndpoint(midx, midy);
    enqueueArc(st, sweep, tool_end, centerx, centery, turn, f);
  } else {  // tangent
    flushQueue(st);
    setEndpoint(cx, cy);
    enqueueArc(st, sweep, tool_end, centerx, centery, turn, f);
  }
  s.current = tool_end;
  s.programmed = end;
}

void BlockExecutor::compOff(Step& st) {
  InterpState& s = st.s;
  if (s.comp_side != CompSide::kOff && s.comp_radius > 0.0 && !s.comp_first_move) {
    moveEndpointAndFlush(st, s.current[kX], s.current[kY]);
    flushQueue(st);
    s.current[kX] = s.programmed[kX];
    s.current[kY] = s.programmed[kY];
    s.current[kZ] = s.programmed[kZ];
  }
  s.comp_side = CompSide::kOff;
  s.comp_first_move = true;
}

}  // namespace mdhd::gcode

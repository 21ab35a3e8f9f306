// G5 (cubic), G5.1 (quadratic B-spline) and G5.2/G5.3 (NURBS) as LinuxCNC 2.9
// defines them (XY plane only), handed on as feed moves along a polyline
// within InterpreterConfig::spline_tolerance of the curve.
#include <cmath>

#include "sim/gcode/block_step.h"
#include "sim/gcode/spline_math.h"

namespace mdhd::gcode {
namespace {

constexpr int kMaxNurbsOrder = 64;  // degree 63: far beyond any CAM output

}  // namespace

void BlockExecutor::spline(Step& st, int motion) {
  InterpState& s = st.s;
  const BlockWords& w = st.w;
  const int column = st.gColumn(kGMotion);
  if (s.comp_side != CompSide::kOff)
    st.fail("Cannot convert spline with cutter radius compensation", column);
  if (s.feed_mode == FeedMode::kInverseTime && !w.has('F'))
    st.fail("F word missing with inverse time arc move", column);
  if (s.feed_mode != FeedMode::kInverseTime && s.feed == 0.0)
    st.fail("Cannot make arc with zero feed rate", column);
  if (s.feed_mode == FeedMode::kUnitsPerRevolution && s.speed == 0.0)
    st.fail("Cannot feed with zero spindle speed in feed per rev mode", column);
  if (s.plane != Plane::kXY) st.fail("Splines must be in the XY plane", column);
  for (char c : {'Z', 'A', 'B', 'C'})
    if (w.has(c)) st.failWord(c, "Splines may not have motion in Z, A, B, or C");
  for (char c : {'U', 'V', 'W'})
    if (w.has(c)) st.failWord(c, "Splines may not have motion in U, V, or W");
  const double x0 = s.current[kX], y0 = s.current[kY];
  std::vector<ControlPoint> points{{x0, y0, 1.0}};
  if (motion == 51) {
    if (!w.has('I') || !w.has('J')) st.fail("Must specify both I and J with G5.1", column);
    points.push_back({x0 + st.lenWord('I'), y0 + st.lenWord('J'), 1.0});
  } else {
    if (w.has('I') != w.has('J')) st.fail("Must specify both I and J, or neither", column);
    // Without I J the curve leaves along the direction the previous G5 ended in
    // (LinuxCNC keeps -P -Q of the last cubic where canned cycles keep I J).
    const double i = w.has('I') ? st.lenWord('I') : s.cycle.i;
    const double j = w.has('J') ? st.lenWord('J') : s.cycle.j;
    points.push_back({x0 + i, y0 + j, 1.0});
  }
  const AxisValues end = findEnd(st);
  if (motion == 50) {
    if (!w.has('P') || !w.has('Q')) st.fail("Must specify both P and Q with G5", column);
    const double p = st.lenWord('P'), q = st.lenWord('Q');
    points.push_back({end[kX] + p, end[kY] + q, 1.0});
    s.cycle.i = -p;
    s.cycle.j = -q;
  }
  points.push_back({end[kX], end[kY], 1.0});
  const int order = static_cast<int>(points.size());
  const NurbsCurve curve(std::move(points), order);
  std::vector<PlanePoint> polyline;
  flattenCurve(curve, {end[kX], end[kY]}, config_.spline_tolerance, polyline);
  emitCurve(st, polyline);
}

// A block under G5.2: the first one starts the curve at the current point
// (its weight is P when the block has no X Y), every block with X Y adds a
// control point of weight P (only the first block may leave it out), L (> 3)
// sets the order.
void BlockExecutor::nurbsPoint(Step& st) {
  InterpState& s = st.s;
  const BlockWords& w = st.w;
  const int column = st.gColumn(kGMotion);
  if (w.has('X') != w.has('Y'))
    st.fail("You must specify both X and Y coordinates for Control Points", column);
  const bool xy = w.has('X');
  const bool first_block = s.motion != 52;
  if (first_block) clearNurbs();
  const double p = w.has('P') ? w.get('P') : -1.0;
  if (!xy && p > 0 && !nurbs_.empty())
    st.fail("Can specify P without X and Y only for the first control point", column);
  // As rs274: the block that starts the curve is not checked (its point then
  // gets weight 1 here); every later point needs P > 0.
  if (xy && p <= 0 && !first_block)
    st.fail("Must specify positive weight P for every Control Point", column);
  if (s.feed_mode == FeedMode::kUnitsPerMinute && s.feed == 0.0)
    st.fail("Cannot make a NURBS with 0 feedrate", column);
  for (char c : {'Z', 'A', 'B', 'C', 'U', 'V', 'W'})
    if (w.has(c)) st.failWord(c, "NURBS control points have X and Y only");
  if (nurbs_.empty()) {
    nurbs_.push_back({s.current[kX], s.current[kY], !xy && p > 0 ? p : 1.0});
    s.nurbs_order = 3;
  }
  if (w.has('L')) {
    const double l = w.get('L');
    if (l != std::floor(l)) st.failWord('L', "NURBS order L must be an integer");
    if (l > kMaxNurbsOrder)
      st.failWord('L', "NURBS order L above " + std::to_string(kMaxNurbsOrder));
    if (l > 3) s.nurbs_order = static_cast<int>(l);
  }
  if (xy) {
    const AxisValues end = findEnd(st);
    nurbs_.push_back({end[kX], end[kY], p > 0 ? p : 1.0});
  }
}

// G5.3: draws the collected curve; the position becomes its last point.
void BlockExecutor::nurbsEnd(Step& st) {
  InterpState& s = st.s;
  const int column = st.w.g_column[kGNonModal];
  if (s.motion != 52) st.fail("Cannot use G5.3 without G5.2 first", column);
  if (static_cast<int>(nurbs_.size()) < s.nurbs_order)
    st.fail("You must specify a number of control points at least equal to the order L = " +
                std::to_string(s.nurbs_order),
            column);
  if (s.feed_mode == FeedMode::kInverseTime && !st.w.has('F'))
    st.fail("F word missing with inverse time arc move", column);
  const ControlPoint last = nurbs_.back();
  const NurbsCurve curve(nurbs_, s.nurbs_order);
  clearNurbs();
  std::vector<PlanePoint> polyline;
  flattenCurve(curve, {last.x, last.y}, config_.spline_tolerance, polyline);
  emitCurve(st, polyline);
  s.motion = 800;  // LinuxCNC: no motion mode until the next motion code
}

void BlockExecutor::emitCurve(Step& st, const std::vector<PlanePoint>& points) {
  InterpState& s = st.s;
  double length = 0.0;
  double x = s.current[kX], y = s.current[kY];
  for (const PlanePoint& p : points) {
    length += std::hypot(p[0] - x, p[1] - y);
    x = p[0];
    y = p[1];
  }
  // Under G93 the whole curve takes 1/F minutes.
  const FeedInfo feed = feedFor(st, length, false);
  AxisValues end = s.current;
  for (const PlanePoint& p : points) {
    end[kX] = p[0];
    end[kY] = p[1];
    emitStraight(st, MotionType::kFeed, end, feed);
  }
}

}  // namespace mdhd::gcode

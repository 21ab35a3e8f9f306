// G0 G1 G2 G3 and the dispatch to canned cycles and cutter compensation.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/gcode/arc_math.h"
#include "sim/gcode/block_step.h"

namespace mdhd::gcode {
namespace {

bool isRotary(int axis) {
  return axis == kA || axis == kB || axis == kC;
}

bool compActive(const InterpState& s) {
  return s.comp_side != CompSide::kOff && s.comp_radius > 0.0;
}

}  // namespace

void BlockExecutor::runMotion(Step& st) {
  const int motion = st.motion;
  InterpState& s = st.s;
  if (!isCycle(motion)) s.cycle.initial_level_set = false;
  if (motion == 800) {
    s.motion = 800;
    return;
  }
  if (isCycle(motion)) {
    cannedCycle(st, motion);
    return;
  }
  if (motion == 50 || motion == 51) {
    spline(st, motion);
    s.motion = motion;
    return;
  }
  if (motion == 52) {
    nurbsPoint(st);
    s.motion = motion;
    return;
  }
  const AxisValues end = findEnd(st);
  if (motion >= 382 && motion <= 385)
    probe(st, end);
  else if (motion == 0 || motion == 10)
    straight(st, motion, end);
  else if (motion == 330 || motion == 331)
    spindleSynced(st, motion, end);
  else
    arc(st, motion, end);
  s.motion = motion;
}

AxisValues BlockExecutor::findEnd(const Step& st) const {
  const InterpState& s = st.s;
  const BlockWords& w = st.w;
  AxisValues end = s.current;
  if (compActive(s)) {  // X and Y continue from the programmed point, not the tool centre
    end[kX] = s.programmed[kX];
    end[kY] = s.programmed[kY];
  }
  if (w.g[kGNonModal] == 530) {  // G53: the words are machine values
    AxisValues machine = toMachine(s, s.current);
    for (int a = 0; a < kAxisCount; ++a)
      if (w.has(kAxisLetters[a]))
        machine[a] = isRotary(a) ? w.get(kAxisLetters[a]) : st.len(w.get(kAxisLetters[a]));
    return toProgram(s, machine);
  }
  for (int a = 0; a < kAxisCount; ++a) {
    const char c = kAxisLetters[a];
    if (!w.has(c)) continue;
    const double v = isRotary(a) ? w.get(c) : st.len(w.get(c));
    end[a] = s.incremental ? end[a] + v : v;
  }
  if (w.hasPolar()) polarEnd(st, end);
  return end;
}

// @ (radius) and ^ (angle, degrees) give X and Y about the program's XY
// origin. G90: a word left out keeps the current radius or angle; G91: each is
// added to the current one. `end` holds the point the move starts from.
void BlockExecutor::polarEnd(const Step& st, AxisValues& end) const {
  const BlockWords& w = st.w;
  const double x = end[kX], y = end[kY];
  const bool at_origin = x == 0.0 && y == 0.0;
  double radius = std::hypot(x, y);
  double angle = std::atan2(y, x);
  const double word_angle = w.angle * std::numbers::pi / 180.0;
  if (st.s.incremental) {
    if (at_origin)
      st.fail(w.has_angle ? "G91 motion with polar coordinates is indeterminate when at the origin"
                          : "Incremental motion with polar coordinates is indeterminate when at "
                            "the origin",
              w.polar_column);
    if (w.has_radius) radius += st.len(w.radius);
    if (w.has_angle) angle += word_angle;
  } else {
    if (!w.has_angle && at_origin)
      st.fail("Must specify angle in polar coordinate if at the origin", w.polar_column);
    if (w.has_radius) radius = st.len(w.radius);
    if (w.has_angle) angle = word_angle;
  }
  end[kX] = radius * std::cos(angle);
  end[kY] = radius * std::sin(angle);
}

FeedInfo BlockExecutor::feedFor(const Step& st, double length, bool rotary_only) const {
  const InterpState& s = st.s;
  FeedInfo f;
  f.mode = s.feed_mode;
  if (s.feed_mode != FeedMode::kInverseTime) {
    f.rate = s.feed;
    f.raw = s.feed_word;
    return f;
  }
  // G93: the rate that makes the move take 1/F minutes (LinuxCNC: at least 0.1).
  const double inverse = st.w.get('F');
  f.inverse_time = inverse;
  if (rotary_only) {
    f.raw = std::max(0.1, length * inverse);
    f.rate = f.raw;
  } else {
    f.raw = std::max(0.1, length / st.unit() * inverse);
    f.rate = f.raw * st.unit();
  }
  return f;
}

void BlockExecutor::emitStraight(Step& st, MotionType type, const AxisValues& end,
                                 const FeedInfo& feed) {
  out_.straight(type, end, st.s, st.block, feed, false);
  st.s.current = end;
  st.s.programmed = end;
}

void BlockExecutor::straight(Step& st, int motion, const AxisValues& end) {
  InterpState& s = st.s;
  const int column = st.gColumn(kGMotion);
  FeedInfo feed;
  if (motion == 10) {
    if (s.feed_mode == FeedMode::kUnitsPerMinute && s.feed == 0.0)
      st.fail("Cannot do G1 with zero feed rate", column);
    if (s.feed_mode == FeedMode::kUnitsPerRevolution) {
      if (s.feed == 0.0) st.fail("Cannot do G1 with zero feed rate", column);
      if (s.speed == 0.0)
        st.fail("Cannot feed with zero spindle speed in feed per rev mode", column);
    }
    if (s.feed_mode == FeedMode::kInverseTime && !st.w.has('F'))
      st.fail("F word missing with inverse time g1 move", column);
    // Length from the programmed point (under compensation) as LinuxCNC measures it.
    const AxisValues& from = compActive(s) ? s.programmed : s.current;
    double lin = 0.0, rot = 0.0;
    for (int a = 0; a < kAxisCount; ++a) {
      const double d = end[a] - from[a];
      (isRotary(a) ? rot : lin) += d * d;
    }
    const bool rotary_only = lin == 0.0 && rot != 0.0;
    feed = feedFor(st, std::sqrt(rotary_only ? rot : lin), rotary_only);
  }
  const MotionType type = motion == 0 ? MotionType::kRapid : MotionType::kFeed;
  if (compActive(s)) {
    if (st.w.g[kGNonModal] == 530)
      st.fail("Cannot use G53 with cutter radius comp", st.w.g_column[kGNonModal]);
    if (s.comp_first_move)
      compStraightFirst(st, type, end, feed);
    else
      compStraight(st, type, end, feed);
    return;
  }
  emitStraight(st, type, end, feed);
}

// G38.2..G38.5: a feed move toward the target that ends where the probe trips
// (InterpreterConfig::probe_stop) or, without a probe model, at the target.
void BlockExecutor::probe(Step& st, const AxisValues& end) {
  InterpState& s = st.s;
  const int column = st.gColumn(kGMotion);
  if (s.comp_side != CompSide::kOff) st.fail("Cannot probe with cutter radius comp on", column);
  if (s.feed_mode == FeedMode::kInverseTime)
    st.fail("Cannot probe in inverse time feed mode", column);
  if (s.feed == 0.0) st.fail("Cannot probe with zero feed rate", column);
  if (s.tool_length_mode == 434) st.fail("Cannot probe under G43.4", column);
  for (int a = kA; a <= kC; ++a)
    if (end[a] != s.current[a]) st.fail("Cannot move rotary axes during probing", column);
  double d2 = 0.0;
  for (int a = kX; a <= kZ; ++a) d2 += (end[a] - s.current[a]) * (end[a] - s.current[a]);
  if (std::sqrt(d2) < 0.254) st.fail("Start of probe move is within 0.01 inch of end", column);
  // The machine rests where the probe model says it trips, else at the target.
  AxisValues stop_program = end;
  bool tripped = false;
  if (config_.probe_stop) {
    AxisValues stop = toMachine(s, end);
    tripped = config_.probe_stop(out_.machine(), toMachine(s, end), stop);
    if (tripped) stop_program = toProgram(s, stop);
  }
  emitStraight(st, MotionType::kFeed, stop_program, feedFor(st, 0.0, false));
  s.probe_point = stop_program;
  s.probe_tripped = tripped;
  ++s.probe_count;
}

// G33 (a feed move locked to the spindle, K = distance per revolution) and
// G33.1 (rigid tapping: in to the target, spindle reversed, out to the start;
// LinuxCNC's RIGID_TAP leaves the position where it was).
void BlockExecutor::spindleSynced(Step& st, int motion, const AxisValues& end) {
  InterpState& s = st.s;
  const int column = st.gColumn(kGMotion);
  const char* name = motion == 330 ? "G33" : "G33.1";
  if (s.spindle == SpindleState::kOff)
    st.fail(std::string("Spindle not turning in ") + name, column);
  if (s.comp_side != CompSide::kOff)
    st.fail(std::string("Cannot use ") + name + " with cutter radius compensation", column);
  if (st.w.g[kGNonModal] == 530) st.fail(std::string("Cannot use ") + name + " with G53", column);
  if (motion == 331) {
    for (int a = kA; a < kAxisCount; ++a)
      if (end[a] != s.current[a]) st.failWord(kAxisLetters[a], "G33.1 moves only X, Y and Z");
  }
  FeedInfo feed;
  feed.mode = FeedMode::kUnitsPerRevolution;
  feed.rate = std::fabs(st.lenWord('K'));
  if (feed.rate == 0.0) st.failWord('K', std::string("Zero pitch (K) with ") + name);
  feed.raw = feed.rate;
  feed.sync = true;
  const AxisValues start = s.current;
  emitStraight(st, MotionType::kFeed, end, feed);
  if (motion == 331) emitStraight(st, MotionType::kFeed, start, feed);
}

void BlockExecutor::arc(Step& st, int motion, const AxisValues& end) {
  InterpState& s = st.s;
  const BlockWords& w = st.w;
  const int column = st.gColumn(kGMotion);
  const bool ccw = motion == 30;
  if (s.tool_length_mode == 434) st.fail("Arcs are not supported under G43.4", column);
  const PlaneAxes axes = planeAxes(s.plane);
  // Centre words of the plane: G17 I J, G18 K I, G19 J K.
  const char l1 = s.plane == Plane::kXY ? 'I' : (s.plane == Plane::kXZ ? 'K' : 'J');
  const char l2 = s.plane == Plane::kXY ? 'J' : (s.plane == Plane::kXZ ? 'I' : 'K');
  const char normal_letter = s.plane == Plane::kXY ? 'K' : (s.plane == Plane::kXZ ? 'J' : 'I');
  const bool ijk = w.has(l1) || w.has(l2);
  if (w.has('R') && ijk) st.fail("Mixed radius-ijk format for arc", column);
  if (!w.has('R') && !ijk) st.fail("R, I, J, and K words all missing for arc", column);
  if (w.has(normal_letter)) {
    static const char* kMsg[] = {"K word given for arc in XY plane",
                                 "J word given for arc in XZ plane",
                                 "I word given for arc in YZ plane"};
    st.failWord(normal_letter, kMsg[static_cast<int>(s.plane)]);
  }
  if (s.feed_mode == FeedMode::kInverseTime && !w.has('F'))
    st.fail("F word missing with inverse time arc move", column);
  if (s.feed_mode != FeedMode::kInverseTime && s.feed == 0.0)
    st.fail("Cannot make arc with zero feed rate", column);
  if (s.feed_mode == FeedMode::kUnitsPerRevolution && s.speed == 0.0)
    st.fail("Cannot feed with zero spindle speed in feed per rev mode", column);
  int turns = 1;
  if (w.has('P')) turns = static_cast<int>(std::lround(w.get('P')));  // checked: >= 1
  double o1 = 0.0, o2 = 0.0;
  if (ijk) {
    if (s.arc_absolute && !w.has(l1))
      st.fail(std::string(1, l1) + " word missing in absolute center arc", column);
    if (s.arc_absolute && !w.has(l2))
      st.fail(std::string(1, l2) + " word missing in absolute center arc", column);
    o1 = w.has(l1) ? st.lenWord(l1) : 0.0;
    o2 = w.has(l2) ? st.lenWord(l2) : 0.0;
  } else {
    const char a1 = kAxisLetters[axes.first], a2 = kAxisLetters[axes.second];
    if (!w.has(a1) && !w.has(a2) && !(w.hasPolar() && s.plane == Plane::kXY)) {
      const char lo = std::min(a1, a2), hi = std::max(a1, a2);
      static const char* kPlane[] = {"XY", "XZ", "YZ"};
      st.fail(std::string(1, lo) + " and " + hi + " words missing for arc in " +
                  kPlane[static_cast<int>(s.plane)] + " plane",
              column);
    }
  }
  const bool comp = compActive(s);
  const AxisValues& from = comp ? s.programmed : s.current;
  const ArcTolerance tol = arcTolerance(s.inch);
  const double s1 = from[axes.first], s2 = from[axes.second];
  const double e1 = end[axes.first], e2 = end[axes.second];
  ArcFit fit;
  std::string error;
  if (w.has('R'))
    error = arcFromRadius(ccw, s1, s2, e1, e2, st.lenWord('R'), turns, tol, fit);
  else
    error = arcFromCenter(ccw, s1, s2, e1, e2, o1, o2, s.arc_absolute, turns, tol, st.unit(),
                          kAxisLetters[axes.first], kAxisLetters[axes.second], fit);
  if (!error.empty()) st.fail(error, column);
  const double length = arcLength(s1, s2, from[axes.normal], fit.center1, fit.center2, fit.turn, e1,
                                  e2, end[axes.normal]);
  const FeedInfo feed = feedFor(st, length, false);
  if (comp) {
    if (s.comp_first_move)
      compArcFirst(st, end, feed, fit);
    else
      compArc(st, end, feed, fit);
    return;
  }
  out_.arc(end, fit.center1, fit.center2, fit.turn, s, st.block, feed, false);
  s.current = end;
  s.programmed = end;
}

}  // namespace mdhd::gcode

// Canned cycles G73 G74 G81..G89 with G98/G99 and L repeats, in all three planes,
// move for move as LinuxCNC 2.9 emits them.
#include <cmath>

#include "sim/gcode/block_step.h"

namespace mdhd::gcode {
namespace {

constexpr double kPeckBackOff = 0.010 * kMmPerInch;  // G83_RAPID_DELTA, 0.010 inch

}  // namespace

// One move of a cycle: (a, b) in the plane, c along its normal.
void BlockExecutor::cycleMove(Step& st, MotionType type, double a, double b, double c) {
  const PlaneAxes axes = planeAxes(st.s.plane);
  AxisValues end = st.s.current;
  end[axes.first] = a;
  end[axes.second] = b;
  end[axes.normal] = c;
  FeedInfo feed;
  if (type == MotionType::kFeed) feed = feedFor(st, 0.0, false);
  emitStraight(st, type, end, feed);
}

void BlockExecutor::cannedCycle(Step& st, int motion) {
  InterpState& s = st.s;
  const BlockWords& w = st.w;
  const int column = st.gColumn(kGMotion);
  if (s.feed == 0.0 && s.feed_mode != FeedMode::kInverseTime)
    st.fail("Cannot feed with zero feed rate", column);
  if (s.feed_mode == FeedMode::kInverseTime)
    st.fail("Cannot use inverse time feed with canned cycles", column);
  if (s.comp_side != CompSide::kOff)
    st.fail("Cannot use canned cycles with cutter compensation on", column);
  if (s.tool_length_mode == 434) st.fail("Cannot use canned cycles under G43.4", column);
  const bool same_mode = s.motion == motion;
  double r_word;
  if (w.has('R'))
    r_word = st.lenWord('R');
  else if (same_mode)
    r_word = s.cycle.r;
  else
    st.fail("R clearance plane unspecified in canned cycle", column);
  int repeats = 1;
  if (w.has('L')) {
    const double l = w.get('L');
    if (l == 0) st.failWord('L', "Cannot do zero repeats of cycle");
    if (l < 0 || l != std::floor(l)) st.failWord('L', "Negative or non-integer L word used");
    repeats = st.intWord('L');
  }
  const PlaneAxes axes = planeAxes(s.plane);
  const char c_letter = kAxisLetters[axes.normal];
  static const char* kPlaneName[] = {"XY", "XZ", "YZ"};
  const std::string plane_name = kPlaneName[static_cast<int>(s.plane)];
  if (!same_mode && !w.has(c_letter))
    st.fail(
        std::string(1, c_letter) + " value unspecified in " + plane_name + " plane canned cycle",
        column);
  const double c_word = w.has(c_letter) ? st.lenWord(c_letter) : s.cycle.bottom;
  if (!s.cycle.initial_level_set) {
    s.cycle.initial_level = s.current[axes.normal];
    s.cycle.initial_level_set = true;
  }
  double old_cc = s.cycle.initial_level;
  const char a_letter = kAxisLetters[axes.first], b_letter = kAxisLetters[axes.second];
  double aa = s.current[axes.first], bb = s.current[axes.second];
  double aa_inc = 0.0, bb_inc = 0.0, r, cc;
  if (w.hasPolar() && (s.incremental || s.plane != Plane::kXY))
    st.fail("Polar coordinates in a canned cycle are supported only in G90 and G17",
            w.polar_column);
  if (s.incremental) {
    if (w.has(a_letter)) aa_inc = st.lenWord(a_letter);
    if (w.has(b_letter)) bb_inc = st.lenWord(b_letter);
    r = r_word + old_cc;
    cc = r + c_word;
  } else {
    if (w.has(a_letter)) aa = st.lenWord(a_letter);
    if (w.has(b_letter)) bb = st.lenWord(b_letter);
    if (w.hasPolar()) {
      AxisValues end = s.current;
      polarEnd(st, end);
      aa = end[kX];
      bb = end[kY];
    }
    r = r_word;
    cc = c_word;
  }
  if (r < cc)
    st.fail(std::string("R less than ") + c_letter + " in cycle in " + plane_name + " plane",
            column);
  // Cycle parameters that must be present the first time.
  double p = w.has('P') ? w.get('P') : -1.0, q = w.has('Q') ? st.lenWord('Q') : -1.0;
  const bool needs_p = motion == 820 || motion == 860 || motion == 880 || motion == 890;
  if (needs_p && !same_mode && p < 0) {
    st.fail("Dwell time P word missing with G" + std::to_string(motion / 10), column);
  }
  if (p < 0) p = s.cycle.p;
  if (motion == 730 || motion == 830) {
    if (!same_mode && q < 0) st.fail("Q word missing with G" + std::to_string(motion / 10), column);
    if (q < 0) q = s.cycle.q;
    if (q <= 0) st.failWord('Q', "Negative or zero Q value used");
  }
  if ((motion == 740 || motion == 840 || motion == 860 || motion == 870 || motion == 880) &&
      s.spindle == SpindleState::kOff)
    st.fail("Spindle not turning in G" + std::to_string(motion / 10), column);
  if (motion == 840 && s.spindle != SpindleState::kClockwise)
    st.fail("Spindle turning counterclockwise in G84", column);
  if (motion == 740 && s.spindle != SpindleState::kCounterClockwise)
    st.fail("Spindle turning clockwise in G74", column);
  double ci = s.cycle.i, cj = s.cycle.j, ck = s.cycle.k;
  if (motion == 870) {  // back boring: I J offsets (plane axes), K top of counterbore
    const char l1 = s.plane == Plane::kXY ? 'I' : (s.plane == Plane::kXZ ? 'K' : 'J');
    const char l2 = s.plane == Plane::kXY ? 'J' : (s.plane == Plane::kXZ ? 'I' : 'K');
    const char l3 = s.plane == Plane::kXY ? 'K' : (s.plane == Plane::kXZ ? 'J' : 'I');
    if (!same_mode && !(w.has(l1) && w.has(l2) && w.has(l3)))
      st.fail(std::string(1, !w.has(l1) ? l1 : (!w.has(l2) ? l2 : l3)) + " word missing with G87",
              column);
    if (w.has(l1)) ci = st.lenWord(l1);
    if (w.has(l2)) cj = st.lenWord(l2);
    if (w.has(l3)) ck = st.lenWord(l3);
  }
  double current_cc = s.current[axes.normal];
  if (old_cc < r) {  // below the R plane: straight up to it first
    cycleMove(st, MotionType::kRapid, s.current[axes.first], s.current[axes.second], r);
    old_cc = r;
    current_cc = r;
  }
  const double clear = s.retract_to_r ? r : old_cc;
  const double middle_k = s.incremental ? cc + ck : ck;
  const SpindleState spindle = s.spindle;
  auto dwell = [&](double seconds) {
    Event e;
    e.type = EventType::kDwell;
    e.value = seconds;
    emitEvent(st, std::move(e));
  };
  auto spindleEvent = [&](SpindleState state) {
    st.s.spindle = state;
    Event e;
    e.type = EventType::kSpindle;
    e.spindle = state;
    e.spindle_rpm = st.s.speed;
    emitEvent(st, std::move(e));
  };
  for (int n = 0; n < repeats; ++n) {
    aa += aa_inc;
    bb += bb_inc;
    // The first positioning move runs at the current level, later ones at
    // the clearance level (LinuxCNC 2.9's CYCLE_MACRO).
    if (n == 0 && current_cc > r) {
      cycleMove(st, MotionType::kRapid, aa, bb, current_cc);
      cycleMove(st, MotionType::kRapid, aa, bb, r);
    } else {
      cycleMove(st, MotionType::kRapid, aa, bb, clear);
      if (clear > r) cycleMove(st, MotionType::kRapid, aa, bb, r);
    }
    switch (motion) {
      case 810:
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        cycleMove(st, MotionType::kRapid, aa, bb, clear);
        break;
      case 820:
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        dwell(p);
        cycleMove(st, MotionType::kRapid, aa, bb, clear);
        break;
      case 730:
      case 830: {
        const double back_off = kPeckBackOff;  // the same length in both unit modes
        for (double depth = r - q; depth > cc; depth -= q) {
          cycleMove(st, MotionType::kFeed, aa, bb, depth);
          if (motion == 830) cycleMove(st, MotionType::kRapid, aa, bb, r);
          cycleMove(st, MotionType::kRapid, aa, bb, depth + back_off);
        }
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        cycleMove(st, MotionType::kRapid, aa, bb, clear);
        break;
      }
      case 740:  // G74: G84 with the spindle turning the other way
      case 840: {
        const bool right = motion == 840;
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        spindleEvent(right ? SpindleState::kCounterClockwise : SpindleState::kClockwise);
        if (p > 0) dwell(p);
        cycleMove(st, MotionType::kFeed, aa, bb, clear);
        spindleEvent(right ? SpindleState::kClockwise : SpindleState::kCounterClockwise);
        break;
      }
      case 850:
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        cycleMove(st, MotionType::kFeed, aa, bb, r);
        cycleMove(st, MotionType::kRapid, aa, bb, clear);
        break;
      case 860:
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        dwell(p);
        spindleEvent(SpindleState::kOff);
        cycleMove(st, MotionType::kRapid, aa, bb, clear);
        spindleEvent(spindle);
        break;
      case 870:
        cycleMove(st, MotionType::kRapid, aa + ci, bb + cj, r);
        spindleEvent(SpindleState::kOff);
        cycleMove(st, MotionType::kRapid, aa + ci, bb + cj, cc);
        cycleMove(st, MotionType::kRapid, aa, bb, cc);
        spindleEvent(spindle);
        cycleMove(st, MotionType::kFeed, aa, bb, middle_k);
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        spindleEvent(SpindleState::kOff);
        cycleMove(st, MotionType::kRapid, aa + ci, bb + cj, cc);
        cycleMove(st, MotionType::kRapid, aa + ci, bb + cj, clear);
        cycleMove(st, MotionType::kRapid, aa, bb, clear);
        spindleEvent(spindle);
        break;
      case 880: {
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        dwell(p);
        spindleEvent(SpindleState::kOff);
        Event stop;
        stop.type = EventType::kProgramStop;
        emitEvent(st, std::move(stop));
        spindleEvent(spindle);
        break;
      }
      case 890:
        cycleMove(st, MotionType::kFeed, aa, bb, cc);
        dwell(p);
        cycleMove(st, MotionType::kFeed, aa, bb, clear);
        break;
      default:
        break;
    }
  }
  // As LinuxCNC: the tool is taken to be at the clearance level (after G88 the
  // operator retracts it by hand).
  s.current[axes.first] = aa;
  s.current[axes.second] = bb;
  s.current[axes.normal] = clear;
  s.programmed = s.current;
  s.cycle.bottom = c_word;
  s.cycle.r = r_word;
  s.cycle.p = p;
  s.cycle.q = q;
  s.cycle.i = ci;
  s.cycle.j = cj;
  s.cycle.k = ck;
  s.motion = motion;
}

}  // namespace mdhd::gcode

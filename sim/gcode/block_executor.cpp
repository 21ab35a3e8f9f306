#include "sim/gcode/block_executor.h"

#include <cmath>

#include "sim/gcode/block_step.h"

namespace mdhd::gcode {

BlockExecutor::BlockExecutor(InterpreterConfig config, MotionSink& sink)
    : config_(std::move(config)), out_(sink, config_.home) {
  // A tiny tolerance would turn one spline into millions of moves.
  if (!(config_.spline_tolerance >= 1e-6))
    throw GcodeError(SourcePos{"configuration", 0, 0},
                     "spline_tolerance must be at least 0.000001 mm");
  for (int i = 0; i < kCoordSystems; ++i)
    for (int a = 0; a < 3; ++a) state_.g5x[i][a] = config_.work_offsets[i][a];
  state_.current = toProgram(state_, config_.home);
  state_.programmed = state_.current;
  queue_.reserve(16);
}

void BlockExecutor::execute(const Block& block) {
  readBlockWords(block, config_.axis_mask, words_);
  InterpState working = state_;
  Step st{block, words_, working};
  nurbs_mark_ = nurbs_.size();
  nurbs_cleared_ = false;
  staged_tool_.reset();
  try {
    executeSteps(st);
  } catch (...) {
    if (nurbs_cleared_) nurbs_.swap(nurbs_backup_);
    nurbs_.resize(nurbs_mark_);
    throw;
  }
  if (staged_tool_) config_.tools.add(*staged_tool_);
  state_ = working;
}

void BlockExecutor::clearNurbs() {
  if (!nurbs_cleared_) {
    nurbs_backup_.swap(nurbs_);  // kept whole until the block succeeds
    nurbs_cleared_ = true;
  }
  nurbs_.clear();
}

void BlockExecutor::executeSteps(Step& st) {
  const Block& block = st.block;
  checkWordUse(st);
  for (const std::string& text : block.messages) {
    Event e;
    e.type = EventType::kMessage;
    e.text = text;
    emitEvent(st, std::move(e));
  }
  runModes(st);
  runNonModal(st);
  if (st.motion >= 0) runMotion(st);
  runStop(st);
}

void BlockExecutor::finish(const Block& last) {
  if (state_.ended) return;
  InterpState working = state_;
  Step st{last, words_, working};
  words_ = BlockWords{};
  words_.g.fill(-1);
  words_.m.fill(-1);
  if (working.comp_side != CompSide::kOff) compOff(st);
  Event e;
  e.type = EventType::kProgramEnd;
  emitEvent(st, std::move(e));
  working.ended = true;
  state_ = working;
}

void BlockExecutor::emitEvent(Step& st, Event e) {
  e.pos = st.block.pos;
  if (!queue_.empty()) {
    Queued q;
    q.kind = Queued::kEvent;
    q.event = std::move(e);
    queue_.push_back(std::move(q));
    return;
  }
  out_.event(e);
}

namespace {

bool usesAxesNonModal(int g0) {
  return g0 == 100 || g0 == 280 || g0 == 300 || g0 == 520 || g0 == 920;
}

bool isCompOn(int g7) {
  return g7 == 410 || g7 == 420 || g7 == 411 || g7 == 421;
}

// Words no code of the block uses, in LinuxCNC's words (check_other_codes);
// `motion` is the motion the block will execute (-1: none).
void checkArgumentLetters(const Block& block, const BlockWords& w, int motion) {
  constexpr auto bit = [](char c) { return 1u << (c - 'A'); };
  constexpr std::uint32_t kChecked = bit('D') | bit('E') | bit('H') | bit('I') | bit('J') |
                                     bit('K') | bit('L') | bit('P') | bit('Q') | bit('R');
  const bool cycle = isCycle(motion);
  const int m_spindle = w.m[kMSpindle];
  const int m_override = w.m[kMOverride];
  if (w.spindle_column != 0 && m_spindle < 0 && m_override != 510 && motion != 330 &&
      motion != 331 && w.g[kGSpindleMode] < 0 && !w.has('S'))
    failAt(block, w.spindle_column,
           "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G96, G97 or S "
           "word to use it");
  // Most blocks (G1 X Y Z F) have none of these: nothing to check.
  if (!(w.letters & kChecked) && !cycle && motion != 330 && motion != 331) return;
  const bool arc = motion == 20 || motion == 30;
  const bool orient = m_spindle == 190;  // M19: R angle, Q timeout, P direction
  const int g0 = w.g[kGNonModal];
  const bool g10 = g0 == 100;
  auto reject = [&](char c, bool unused, const char* text) {
    if (unused && w.has(c)) failAt(block, w.col(c), text);
  };
  reject('A', cycle, "Cannot put an a in canned cycle");
  reject('B', cycle, "Cannot put a b in canned cycle");
  reject('C', cycle, "Cannot put a c in canned cycle");
  const int g7 = w.g[kGCutterComp];
  reject('D', !isCompOn(g7) && w.g[kGSpindleMode] != 960,
         "D word with no G41, G41.1, G42, G42.1, or G96 to use it");
  const int m_io = w.m[kMIo];
  const bool analog_out = m_io == 670 || m_io == 680;
  reject('E', m_io != 660 && !analog_out, "E word with no G76, M66, M67 or M68 to use it");
  const int g8 = w.g[kGToolLength];
  reject('H', g8 != 430 && g8 != 432 && g8 != 434, "H word with no G43 or G76 to use it");
  const bool ij_used = arc || motion == 50 || motion == 51 || motion == 870 || g10;
  reject('I', !ij_used, "I word with no G2, G3, G5, G5.1, G10, G76, or G87 to use it");
  reject('J', !ij_used, "J word with no G2, G3, G5, G5.1, G10, G76 or G87 to use it");
  reject('K', !arc && motion != 330 && motion != 331 && motion != 870,
         "K word with no G2, G3, G33, G33.1, G76, or G87 to use it");
  reject('L', !cycle && motion != 52 && !g10 && !isCompOn(g7) && m_io != 660,
         "L word with no G10, cutter compensation, canned cycle, digital/analog input, or NURBS "
         "code");
  const bool p_used = g10 || g0 == 40 || w.g[kGPathMode] == 640 || arc || motion == 50 ||
                      motion == 52 || motion == 740 || motion == 820 || motion == 840 ||
                      motion == 860 || motion == 880 || motion == 890 ||
                      (m_override >= 500 && m_override <= 530) || (m_io >= 0 && !analog_out) ||
                      orient;
  reject('P', !p_used,
         "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 "
         "M63 M64 M65 M66 or user M code to use it");
  if ((arc || orient) && w.has('P')) {
    const double p = w.get('P');
    if (std::fabs(std::round(p) - p) > 0.001)
      failAt(block, w.col('P'), "P value not an integer with M19 G2 or G3");
    if (arc && std::round(p) < 1)
      failAt(block, w.col('P'), "P value should be 1 or greater with G2 or G3");
  }
  reject('Q',
         motion != 830 && motion != 730 && motion != 50 && !g10 && w.m[kMToolChange] != 610 &&
             w.g[kGPathMode] != 640 && m_io != 660 && !analog_out && !orient,
         "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that uses "
         "it");
  reject('R', !arc && !cycle && !g10 && g7 != 411 && g7 != 421 && !orient,
         "R word with no G code that uses it");
  if (motion == 330 || motion == 331) {
    if (!w.has('K')) failAt(block, 0, "K word missing with g33");
    reject('F', true, "F word used with a g33");
  }
}

}  // namespace

void BlockExecutor::checkWordUse(Step& st) {
  const BlockWords& w = st.w;
  const int g0 = w.g[kGNonModal];
  const int g8 = w.g[kGToolLength];
  const bool nonmodal_axes = usesAxesNonModal(g0) || g8 == 431 || g8 == 432;
  const int explicit_motion = w.g[kGMotion];
  if (w.hasPolar()) {
    if (nonmodal_axes) st.fail("Polar coordinates can only be used for motion", w.polar_column);
    if (w.has('X')) st.failWord('X', "Cannot specify both polar coordinate and X word");
    if (w.has('Y')) st.failWord('Y', "Cannot specify both polar coordinate and Y word");
    if (g0 == 530) st.fail("Cannot use polar coordinates with G53", w.polar_column);
  }
  if (explicit_motion >= 0) {
    if (explicit_motion == 800 && w.hasAxis() && !nonmodal_axes)
      st.fail("Cannot use axis values with G80", w.axis_column);
    if (explicit_motion != 800 && usesAxesNonModal(g0))
      st.fail("Cannot use two G codes that both use axis values", w.g_column[kGNonModal]);
    st.motion = explicit_motion;
  } else if (w.hasAxis() && !nonmodal_axes) {
    if (st.s.motion == 800)
      st.fail("Cannot use axis values without a g code that uses them", w.axis_column);
    st.motion = st.s.motion;
  }
  if (g0 == 530) {
    if (st.motion != 0 && st.motion != 10)
      st.fail("Must use G0 or G1 with G53", w.g_column[kGNonModal]);
    const bool incremental = w.g[kGDistance] == 910 || (w.g[kGDistance] < 0 && st.s.incremental);
    if (incremental) st.fail("Cannot use G53 incremental", w.g_column[kGNonModal]);
  }
  const int motion_for_words = explicit_motion == 800 ? 800 : (st.motion >= 0 ? st.motion : -1);
  checkArgumentLetters(st.block, w, motion_for_words);
  if (w.has('F') && w.get('F') < 0) st.failWord('F', "Negative F word used");
  if (w.has('S') && w.get('S') < 0) st.failWord('S', "Negative spindle speed used");
  if (w.has('T') && (w.get('T') < 0 || w.get('T') != std::floor(w.get('T'))))
    st.failWord('T', "Negative or non-integer T word used");
}

void BlockExecutor::runModes(Step& st) {
  setFeedMode(st);
  if (st.w.has('F') && st.s.feed_mode != FeedMode::kInverseTime) {
    st.s.feed_word = st.w.get('F');
    st.s.feed = st.lenWord('F');
  }
  if (st.w.has('S')) st.s.speed = st.w.get('S');
  setTool(st);
  setSpindleAndCoolant(st);
  setOverrides(st);
  checkIo(st);
  if (st.w.g[kGNonModal] == 40) {
    if (!st.w.has('P')) st.fail("Dwell time missing with G4", st.w.g_column[kGNonModal]);
    if (st.w.get('P') < 0) st.failWord('P', "Negative dwell time with G4");
    Event e;
    e.type = EventType::kDwell;
    e.value = st.w.get('P');
    emitEvent(st, std::move(e));
  }
  setPlane(st);
  setUnits(st);
  setCutterComp(st);
  setToolLength(st);
  setCoordSystem(st);
  if (st.w.g[kGPathMode] >= 0) st.s.path_mode = st.w.g[kGPathMode];
  if (st.w.g[kGDistance] >= 0) st.s.incremental = st.w.g[kGDistance] == 910;
  if (st.w.g[kGArcDistance] >= 0) st.s.arc_absolute = st.w.g[kGArcDistance] == 901;
  if (st.w.g[kGRetract] >= 0) st.s.retract_to_r = st.w.g[kGRetract] == 990;
}

// M48..M53: LinuxCNC's override switches; they only change what #<_feed_override>,
// #<_speed_override>, #<_adaptive_feed> and #<_feed_hold> read (P0 off, else on).
void BlockExecutor::setOverrides(Step& st) {
  const int m = st.w.m[kMOverride];
  if (m < 0) return;
  const bool on = !(st.w.has('P') && st.w.get('P') == 0.0);
  InterpState& s = st.s;
  if (m == 480 || m == 490) s.feed_override = s.speed_override = m == 480;
  if (m == 500) s.feed_override = on;
  if (m == 510) s.speed_override = on;
  if (m == 520) s.adaptive_feed = on;
  if (m == 530) s.feed_hold = on;
}

// M62..M65 (digital outputs), M66 (wait on an input) and M67/M68 (analog
// outputs): no motion and no event, only LinuxCNC's checks of their words.
void BlockExecutor::checkIo(Step& st) {
  const BlockWords& w = st.w;
  const int m = w.m[kMIo];
  if (m < 0) return;
  const int column = w.m_column[kMIo];
  if (m == 670 || m == 680) {  // E: the output (rounded, from 0), Q: its value
    if (!w.has('E') || std::floor(w.get('E') + 0.5) < 0)
      st.fail("Invalid analog index with M" + std::to_string(m / 10) +
                  " (an E word from 0 names the output)",
              column);
    return;
  }
  if (m != 660) {
    if (!w.has('P')) st.fail("No valid P word with M" + std::to_string(m / 10), column);
    return;
  }
  // LinuxCNC rounds P, E, L and Q to integers here (floor(x + 0.5)).
  auto rounded = [&](char c) { return static_cast<long>(std::floor(w.get(c) + 0.5)); };
  if (w.has('L')) {
    const double l = w.get('L');
    if (l < 0) st.failWord('L', "Negative l word used");
    if (l != std::floor(l)) st.failWord('L', "Non integer value for integer");
  }
  if (w.has('P') && w.has('E'))
    st.fail("Invalid to select both a digital and an analog input with M66", column);
  const long wait_type = w.has('L') ? rounded('L') : 0;
  const long timeout = w.has('Q') ? rounded('Q') : -1;
  if (wait_type > 0 && timeout <= 0)
    st.fail("Zero timeout with wait type != immediate return", column);
  if (w.has('E') && wait_type != 0)
    st.fail("Can't select analog input with wait type != immediate return", column);
  if ((w.has('P') && rounded('P') < 0) || (w.has('E') && rounded('E') < 0) ||
      (!w.has('P') && !w.has('E')))
    st.fail("Need to have either a valid P or a valid E word with M66", column);
}

void BlockExecutor::runNonModal(Step& st) {
  switch (st.w.g[kGNonModal]) {
    case 100:
      setOffsetsG10(st);
      break;
    case 280:
    case 300:
      goToStored(st, st.w.g[kGNonModal] == 300);
      break;
    case 281:
    case 301: {
      if (st.s.comp_side != CompSide::kOff)
        st.fail("Cannot set reference point with cutter compensation in effect",
                st.w.g_column[kGNonModal]);
      AxisValues& stored = st.w.g[kGNonModal] == 281 ? st.s.g28 : st.s.g30;
      stored = toMachine(st.s, st.s.current);
      break;
    }
    case 53:
      nurbsEnd(st);
      break;
    case 520:
    case 920:
    case 921:
    case 922:
    case 923:
      setG92(st);
      break;
    default:
      break;
  }
}

void BlockExecutor::runStop(Step& st) {
  const int stop = st.w.m[kMStop];
  if (stop < 0) return;
  Event e;
  if (stop == 0 || stop == 10 || stop == 600) {
    e.type = EventType::kProgramStop;
    e.value = stop / 10.0;
    emitEvent(st, std::move(e));
    return;
  }
  // M2 / M30: LinuxCNC's end-of-program reset.
  InterpState& s = st.s;
  if (s.comp_side != CompSide::kOff) compOff(st);
  const AxisValues machine = toMachine(s, s.current);
  importCoordSystem(s, 0);
  s.coord_system = 0;
  s.current = toProgram(s, machine);
  s.programmed = s.current;
  s.plane = Plane::kXY;
  s.incremental = false;
  s.feed_mode = FeedMode::kUnitsPerMinute;
  s.feed = 0.0;
  s.feed_word = 0.0;
  s.motion = 10;
  s.cycle.initial_level_set = false;
  if (s.spindle != SpindleState::kOff) {
    s.spindle = SpindleState::kOff;
    Event sp;
    sp.type = EventType::kSpindle;
    sp.spindle = SpindleState::kOff;
    emitEvent(st, std::move(sp));
  }
  if (s.mist || s.flood) {
    s.mist = s.flood = false;
    Event c;
    c.type = EventType::kCoolant;
    emitEvent(st, std::move(c));
  }
  e.type = EventType::kProgramEnd;
  e.value = stop / 10.0;
  emitEvent(st, std::move(e));
  s.ended = true;
}

}  // namespace mdhd::gcode

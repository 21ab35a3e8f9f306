// Modal settings of a block: feed mode, tools, spindle, coolant, plane, units,
// cutter compensation, tool length, coordinate system.
#include <cmath>
#include <exception>
#include <string>

#include "sim/gcode/block_step.h"

namespace mdhd::gcode {

void BlockExecutor::setFeedMode(Step& st) {
  const int g = st.w.g[kGFeedMode];
  if (g < 0) return;
  if (g == 930) {
    st.s.feed_mode = FeedMode::kInverseTime;
    return;
  }
  // G94 and G95 zero the feed rate, as LinuxCNC does (a same-line F sets it again).
  st.s.feed_mode = g == 940 ? FeedMode::kUnitsPerMinute : FeedMode::kUnitsPerRevolution;
  st.s.feed = 0.0;
  st.s.feed_word = 0.0;
}

// LinuxCNC re-reads its position from the machine after M6 and M61 (and a
// probe move), and nowhere else. Where the interpreter's point and the machine
// disagree (a bare G40 leaves the tool centre off the programmed point), the
// machine wins: an axis a later move leaves out keeps the tool-centre value.
void BlockExecutor::resyncFromMachine(InterpState& s) const {
  s.current = toProgram(s, out_.machine());
  s.programmed = s.current;
}

void BlockExecutor::setTool(Step& st) {
  InterpState& s = st.s;
  if (st.w.has('T')) {
    const int t = st.intWord('T');
    if (t != 0 && !config_.tools.find(t))
      st.failWord('T', "Requested tool " + std::to_string(t) + " not found in the tool table");
    s.selected_tool = t;
  }
  const int m = st.w.m[kMToolChange];
  if (m == 60) {
    if (s.selected_tool < 0)
      st.fail("Need tool prepared -Txx- for toolchange", st.w.m_column[kMToolChange]);
    if (s.comp_side != CompSide::kOff)
      st.fail("Cannot change tools with cutter radius compensation on",
              st.w.m_column[kMToolChange]);
    if (s.spindle != SpindleState::kOff) {
      s.spindle = SpindleState::kOff;
      Event e;
      e.type = EventType::kSpindle;
      emitEvent(st, std::move(e));
    }
    // The machine does not move: LinuxCNC re-reads its position after M6, so a
    // G43 of the same block changes the program Z, not the machine Z (rs274's
    // standalone canon differs, see the oracle test).
    resyncFromMachine(s);
    s.tool = s.selected_tool;
    Event e;
    e.type = EventType::kToolChange;
    e.tool = s.tool;
    emitEvent(st, std::move(e));
  } else if (m == 610) {
    if (!st.w.has('Q')) st.fail("Q word missing with M61", st.w.m_column[kMToolChange]);
    const double q = st.w.get('Q');
    const int t = st.intWord('Q');
    if (q < 0 || q != t) st.failWord('Q', "Need non-negative integer Q word with M61");
    if (t != 0 && !config_.tools.find(t))
      st.failWord('Q', "Requested tool " + std::to_string(t) + " not found in the tool table");
    resyncFromMachine(s);  // M61 re-reads the position as M6 does
    s.tool = t;
    Event e;
    e.type = EventType::kToolChange;
    e.tool = t;
    emitEvent(st, std::move(e));
  }
}

void BlockExecutor::setSpindleAndCoolant(Step& st) {
  InterpState& s = st.s;
  const int sp = st.w.m[kMSpindle];
  if (sp == 190) {  // M19: LinuxCNC's checks; orienting stops the spindle
    const BlockWords& w = st.w;
    if (w.has('P') && (std::round(w.get('P')) < 0 || std::round(w.get('P')) > 2))
      st.failWord('P', "P value must be 0,1,or 2 with M19");
    if (w.has('R') && (w.get('R') < 0 || w.get('R') > 360))
      st.failWord('R', "R value must be within 0..360 with M19");
    if (w.has('Q') && w.get('Q') <= 0) st.failWord('Q', "Q word with M19 requires a value > 0");
  }
  if (sp >= 0 || (st.w.has('S') && s.spindle != SpindleState::kOff)) {
    if (sp == 30) s.spindle = SpindleState::kClockwise;
    if (sp == 40) s.spindle = SpindleState::kCounterClockwise;
    if (sp == 50 || sp == 190) s.spindle = SpindleState::kOff;
    Event e;
    e.type = EventType::kSpindle;
    e.spindle = s.spindle;
    e.spindle_rpm = s.speed;
    emitEvent(st, std::move(e));
  }
  const int c = st.w.m[kMCoolant];
  if (c < 0) return;
  if (c == 90) {
    s.mist = s.flood = false;
  } else {
    s.mist = s.mist || c == 70 || st.w.mist_and_flood;
    s.flood = s.flood || c == 80 || st.w.mist_and_flood;
  }
  Event e;
  e.type = EventType::kCoolant;
  e.value = s.flood ? 2.0 : (s.mist ? 1.0 : 0.0);
  emitEvent(st, std::move(e));
}

void BlockExecutor::setPlane(Step& st) {
  const int g = st.w.g[kGPlane];
  if (g < 0) return;
  const Plane p = g == 170 ? Plane::kXY : (g == 180 ? Plane::kXZ : Plane::kYZ);
  if (p != Plane::kXY && st.s.comp_side != CompSide::kOff)
    st.fail(p == Plane::kXZ ? "Cannot use XZ plane with cutter radius comp"
                            : "Cannot use YZ plane with cutter radius comp",
            st.w.g_column[kGPlane]);
  st.s.plane = p;
}

void BlockExecutor::setUnits(Step& st) {
  const int g = st.w.g[kGUnits];
  if (g < 0) return;
  const bool inch = g == 200;
  if (inch != st.s.inch && st.s.comp_side != CompSide::kOff)
    st.fail("Cannot change units with cutter radius comp", st.w.g_column[kGUnits]);
  // Positions are kept in mm, so a unit switch moves nothing.
  st.s.inch = inch;
}

void BlockExecutor::setCutterComp(Step& st) {
  const int g = st.w.g[kGCutterComp];
  if (g < 0) return;
  InterpState& s = st.s;
  const int column = st.w.g_column[kGCutterComp];
  if (g == 400) {
    compOff(st);
    return;
  }
  if (s.comp_side != CompSide::kOff)
    st.fail("Cannot turn cutter radius comp on when already on", column);
  if (s.plane != Plane::kXY) st.fail("Cutter radius compensation allowed only in XY plane", column);
  double radius = 0.0;
  if (g == 411 || g == 421) {
    if (!st.w.has('D')) st.fail("G41.1/G42.1 needs a D word (the diameter)", column);
    radius = st.lenWord('D') / 2.0;
  } else {
    int tool = s.tool;
    if (st.w.has('D')) {
      const double d = st.w.get('D');
      if (d < 0 || d != std::floor(d)) st.failWord('D', "Negative or non-integer D word used");
      tool = st.intWord('D');
      if (tool == 0) tool = s.tool;  // D0: LinuxCNC's pocket 0, the tool in the spindle
    }
    if (tool != 0) {
      const ToolEntry* entry = config_.tools.find(tool);
      if (!entry)
        st.failWord('D', "Requested tool " + std::to_string(tool) + " not found in the tool table");
      radius = entry->diameter / 2.0;
    }
  }
  bool left = g == 410 || g == 411;
  if (radius < 0) {  // a negative diameter swaps the side, as in LinuxCNC
    radius = -radius;
    left = !left;
  }
  s.comp_side = left ? CompSide::kLeft : CompSide::kRight;
  s.comp_radius = radius;
  s.comp_first_move = true;
  s.programmed = s.current;
}

void BlockExecutor::setToolLength(Step& st) {
  const int g = st.w.g[kGToolLength];
  if (g < 0) return;
  InterpState& s = st.s;
  const int column = st.w.g_column[kGToolLength];
  if (s.comp_side != CompSide::kOff)
    st.fail("Cannot change tool offset with cutter radius compensation on", column);
  AxisValues machine = toMachine(s, s.current);
  auto lengthOf = [&](int tool) {
    if (tool == 0) return 0.0;
    const ToolEntry* entry = config_.tools.find(tool);
    if (!entry)
      st.failWord('H', "Requested tool " + std::to_string(tool) + " not found in the tool table");
    return entry->length;
  };
  const bool wasTcp = s.tool_length_mode == 434;
  const double tcpLength = wasTcp ? lengthOf(s.tool_length_tool) : 0.0;
  auto hWord = [&]() {
    const double h = st.w.get('H');
    if (h < 0 || h != std::floor(h)) st.failWord('H', "Negative or non-integer H word used");
    // H0 is LinuxCNC's pocket 0: the tool in the spindle.
    return h == 0 ? s.tool : st.intWord('H');
  };
  switch (g) {
    case 430: {
      const int tool = st.w.has('H') ? hWord() : s.tool;
      s.tool_length = lengthOf(tool);
      s.tool_length_tool = tool;
      break;
    }
    case 431:
      if (st.w.has('X') || st.w.has('Y'))
        st.fail("G43.1 offsets other than Z are not supported", column);
      if (st.w.has('Z')) s.tool_length = st.lenWord('Z');
      s.tool_length_tool = -1;
      break;
    case 432:  // G43.2: an additional offset on top of the one in effect
      if (s.tool_length_mode == 434) st.fail("Cannot use G43.2 under G43.4", column);
      if (!st.w.has('H') && !st.w.hasAxis())
        st.fail("G43.2: No axes specified and H word missing", column);
      if (st.w.has('H') && st.w.hasAxis())
        st.fail("G43.2: Can not have both H and axis words", column);
      for (char c : {'X', 'Y', 'A', 'B', 'C', 'U', 'V', 'W'})
        if (st.w.has(c)) st.failWord(c, "G43.2 offsets other than Z are not supported");
      s.tool_length += st.w.has('H') ? lengthOf(hWord()) : st.lenWord('Z');
      break;
    case 434: {
      const int tool = st.w.has('H') ? hWord() : s.tool;
      if (tool == 0) st.fail("G43.4 needs a tool: H word or a tool in the spindle", column);
      lengthOf(tool);  // must exist
      s.tool_length = 0.0;
      s.tool_length_tool = tool;
      break;
    }
    default:  // G49
      s.tool_length = 0.0;
      s.tool_length_tool = 0;
      break;
  }
  s.tool_length_mode = g;
  const bool isTcp = g == 434;
  const double newTcpLength = isTcp ? lengthOf(s.tool_length_tool) : 0.0;
  if ((wasTcp || isTcp) && (wasTcp != isTcp || tcpLength != newTcpLength) && config_.tcp_switch) {
    // The machine does not move, but under G43.4 its X Y Z are the tip in W: an axis
    // the next block leaves out must stay where the machine is, not where the old
    // meaning of its value would put it (G49 after G43.4 once moved Y to the tip's Y).
    try {
      if (wasTcp) machine = config_.tcp_switch(machine, tcpLength, false);
      if (isTcp) machine = config_.tcp_switch(machine, newTcpLength, true);
    } catch (const std::exception& e) {
      st.fail(std::string(isTcp ? "Cannot start" : "Cannot leave") + " G43.4 here: " + e.what(),
              column);
    }
    out_.reexpress(machine);
  }
  s.current = toProgram(s, machine);  // the machine does not move
  s.programmed = s.current;
}

void BlockExecutor::setCoordSystem(Step& st) {
  const int g = st.w.g[kGCoordSystem];
  if (g < 0) return;
  InterpState& s = st.s;
  if (s.comp_side != CompSide::kOff)
    st.fail("Cannot change coordinate systems with cutter radius comp",
            st.w.g_column[kGCoordSystem]);
  const int index = g <= 590 ? (g - 540) / 10 : 6 + (g - 591);
  const AxisValues machine = toMachine(s, s.current);
  importCoordSystem(s, index);  // re-read even when it is the active one, as LinuxCNC does
  s.coord_system = index;
  s.current = toProgram(s, machine);
  s.programmed = s.current;
}

}  // namespace mdhd::gcode

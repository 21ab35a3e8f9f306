// G10 L2/L20 work offsets, G92 family, G28/G30 returns.
#include <cmath>
#include <numbers>

#include "sim/gcode/block_step.h"

namespace mdhd::gcode {
namespace {

bool isRotary(int axis) {
  return axis == kA || axis == kB || axis == kC;
}

// The word value of an axis in mm (linear) or degrees (rotary).
double axisWord(const BlockExecutor&, const BlockWords& w, int axis, double unit) {
  const double v = w.get(kAxisLetters[axis]);
  return isRotary(axis) ? v : v * unit;
}

}  // namespace

void BlockExecutor::setOffsetsG10(Step& st) {
  InterpState& s = st.s;
  const int column = st.w.g_column[kGNonModal];
  if (!st.w.has('L')) st.fail("Line number missing with G10", column);
  const double l = st.w.get('L');
  if (l != 2 && l != 20)
    st.failWord('L',
                "G10 L" + std::to_string(static_cast<int>(l)) + " is not supported (only L2, L20)");
  if (!st.w.has('P')) st.fail("P word missing with G10", column);
  const double p = st.w.get('P');
  if (p != std::floor(p) || p < 0 || p > kCoordSystems)
    st.failWord('P', "P value out of range with G10 L" + std::to_string(static_cast<int>(l)));
  const int index = p == 0 ? s.coord_system : static_cast<int>(p) - 1;
  const bool active = index == s.coord_system;
  if (active && s.comp_side != CompSide::kOff)
    st.fail("Cannot change coordinate systems with cutter radius comp", column);
  if (l == 20 && st.w.has('R')) st.failWord('R', "R word with no G code that uses it");
  const AxisValues machine = toMachine(s, s.current);
  AxisValues& offset = s.g5x[index];
  if (l == 2) {
    for (int a = 0; a < kAxisCount; ++a)
      if (st.w.has(kAxisLetters[a])) offset[a] = axisWord(*this, st.w, a, st.unit());
    if (st.w.has('R')) s.rotation[index] = st.w.get('R');
  } else {
    // L20: the offset that makes the current point read the given values.
    InterpState probe = s;
    probe.coord_system = index;
    AxisValues wanted = toProgram(probe, machine);
    for (int a = 0; a < kAxisCount; ++a)
      if (st.w.has(kAxisLetters[a])) wanted[a] = axisWord(*this, st.w, a, st.unit());
    probe.g5x[index] = AxisValues{};
    const AxisValues zero_offset = toMachine(probe, wanted);
    for (int a = 0; a < kAxisCount; ++a)
      if (st.w.has(kAxisLetters[a])) offset[a] = machine[a] - zero_offset[a];
  }
  if (active) {
    s.current = toProgram(s, machine);
    s.programmed = s.current;
  }
}

void BlockExecutor::setG92(Step& st) {
  InterpState& s = st.s;
  const int g = st.w.g[kGNonModal];
  if (s.comp_side != CompSide::kOff)
    st.fail("Cannot change axis offsets with cutter radius comp", st.w.g_column[kGNonModal]);
  const AxisValues machine = toMachine(s, s.current);
  if (g == 920) {
    if (!st.w.hasAxis()) st.fail("All axes missing with G92", st.w.g_column[kGNonModal]);
    for (int a = 0; a < kAxisCount; ++a) {
      if (!st.w.has(kAxisLetters[a])) continue;
      const double v = axisWord(*this, st.w, a, st.unit());
      s.g92[a] = s.current[a] + s.g92[a] - v;
      s.current[a] = v;
    }
    s.g92_saved = s.g92;
    s.g92_applied = true;
  } else {
    if (g == 921) s.g92_saved = AxisValues{};
    if (g == 923) {
      s.g92 = s.g92_saved;
      s.g92_applied = true;
    } else {
      s.g92 = AxisValues{};
      s.g92_applied = false;
    }
    s.current = toProgram(s, machine);
  }
  s.programmed = s.current;
}

void BlockExecutor::goToStored(Step& st, bool second) {
  InterpState& s = st.s;
  if (s.comp_side != CompSide::kOff)
    st.fail("Cannot use G28 or G30 with cutter radius compensation", st.w.g_column[kGNonModal]);
  if (s.tool_length_mode == 434)
    st.fail("Cannot use G28 or G30 with G43.4 on", st.w.g_column[kGNonModal]);
  // First the intermediate point (axis words, G90/G91 as usual), then the stored
  // machine position for the named axes (all axes when none is named).
  const AxisValues middle = findEnd(st);
  FeedInfo none;
  emitStraight(st, MotionType::kRapid, middle, none);
  AxisValues target_machine = toMachine(s, middle);
  const AxisValues& stored = second ? s.g30 : s.g28;
  const bool all = !st.w.hasAxis();
  for (int a = 0; a < kAxisCount; ++a)
    if (all || st.w.has(kAxisLetters[a])) target_machine[a] = stored[a];
  emitStraight(st, MotionType::kRapid, toProgram(s, target_machine), none);
}

}  // namespace mdhd::gcode

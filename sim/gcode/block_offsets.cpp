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

// G54..G59.3 number `index` (0..8) as the parameters hold it: #5221+20i.. axes, #5230+20i rotation.
void BlockExecutor::importCoordSystem(InterpState& s, int index) const {
  if (!params_) return;
  const int base = 5221 + 20 * index;
  for (int a = 0; a < kAxisCount; ++a) s.g5x[index][a] = params_->get(base + a);
  s.rotation[index] = params_->get(base + 9);
}

void BlockExecutor::setOffsetsG10(Step& st) {
  InterpState& s = st.s;
  const int column = st.w.g_column[kGNonModal];
  if (!st.w.has('L')) st.fail("Line number missing with G10", column);
  const double l = st.w.get('L');
  if (l == 1 || l == 10 || l == 11) {
    setToolG10(st, static_cast<int>(l));
    return;
  }
  if (l != 2 && l != 20)
    st.failWord('L', "G10 L" + std::to_string(st.intWord('L')) +
                         " is not supported (only L1, L2, L10, L11, L20)");
  if (!st.w.has('P')) st.fail("P word missing with G10", column);
  const double p = st.w.get('P');
  if (p != std::floor(p) || p < 0 || p > kCoordSystems)
    st.failWord('P', "P value out of range with G10 L" + std::to_string(static_cast<int>(l)));
  const int index = p == 0 ? s.coord_system : static_cast<int>(p) - 1;
  const bool active = index == s.coord_system;
  if (active && s.comp_side != CompSide::kOff)
    st.fail("Cannot change coordinate systems with cutter radius comp", column);
  if (l == 20 && st.w.has('R')) st.failWord('R', "R not allowed in G10 L20");
  if (st.w.has('I') || st.w.has('J'))
    st.fail("I J words not allowed with G10 L" + std::to_string(static_cast<int>(l)), column);
  // The current point in the old offsets, before the system is re-read.
  const AxisValues machine = toMachine(s, s.current);
  // LinuxCNC re-expresses the current point of the active system as if no G92
  // offset were in effect: where G10 L2 R changes the rotation while G92 is set,
  // the program point it keeps is not where the machine is (see reexpressed).
  InterpState no_g92 = s;
  no_g92.g92 = AxisValues{};
  const AxisValues machine_no_g92 = toMachine(no_g92, s.current);
  importCoordSystem(s, index);
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
    // Under a rotation X and Y of the offset both change when either is named:
    // the axis left out keeps reading what it read (as in LinuxCNC).
    const bool xy = st.w.has('X') || st.w.has('Y');
    for (int a = 0; a < kAxisCount; ++a)
      if (st.w.has(kAxisLetters[a]) || (xy && (a == kX || a == kY)))
        offset[a] = machine[a] - zero_offset[a];
  }
  if (active) {
    no_g92.g5x = s.g5x;
    no_g92.rotation = s.rotation;
    s.current = toProgram(no_g92, machine_no_g92);
    s.programmed = s.current;
  }
}

// G10 L1 / L10 / L11 P<tool>: edit the tool table. L1 sets the length (Z) and
// radius (R) directly; L10 sets the length that makes the current Z read the Z
// word with that offset; L11 does the same in G59.3 without G92. The offset in
// effect changes only with the next G43, as in LinuxCNC.
void BlockExecutor::setToolG10(Step& st, int l) {
  InterpState& s = st.s;
  const BlockWords& w = st.w;
  const int column = w.g_column[kGNonModal];
  const std::string name = "G10 L" + std::to_string(l);
  if (!w.has('P')) st.fail("P word missing with " + name, column);
  const double p = w.get('P');
  if (p != std::floor(p) || p < 1) st.failWord('P', "Tool number P must be a positive integer");
  const int number = st.intWord('P');
  const ToolEntry* found = config_.tools.find(number);
  if (!found)
    st.failWord('P', "Requested tool " + std::to_string(number) + " not found in the tool table");
  if (!w.has('Z') && !w.has('R') && !w.hasAxis() && !w.has('I') && !w.has('J') && !w.has('Q'))
    st.fail("G10 L1 without offsets has no effect", column);
  for (char c : {'X', 'Y', 'A', 'B', 'C', 'U', 'V', 'W'})
    if (w.has(c)) st.failWord(c, name + ": only Z (length) and R (radius) offsets are kept");
  for (char c : {'I', 'J', 'Q'})
    if (w.has(c)) st.failWord(c, name + ": lathe tool angles and orientation are not supported");
  ToolEntry tool = *found;
  if (w.has('Z')) {
    const double z = st.lenWord('Z');
    if (l == 1) {
      tool.length = z;
    } else {
      // Z of the current point with no tool length offset: in the active system
      // (with G92) for L10, in G59.3 without G92 for L11.
      const double offset = s.tool_length_mode == 434 ? 0.0 : s.tool_length;
      const double here =
          l == 10 ? s.current[kZ] + offset : toMachine(s, s.current)[kZ] - offset - s.g5x[8][kZ];
      tool.length = here - z;
    }
  }
  if (w.has('R')) tool.diameter = 2.0 * st.lenWord('R');
  staged_tool_ = tool;  // into the table when the whole block succeeds
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
  } else if (g == 520) {
    // G52 (LinuxCNC's local offset): the named axes' G92 offsets become the words
    // (G91 or not); the others keep theirs. The machine stays where it is.
    if (!st.w.hasAxis()) st.fail("All axes missing with G52", st.w.g_column[kGNonModal]);
    for (int a = 0; a < kAxisCount; ++a)
      if (st.w.has(kAxisLetters[a])) s.g92[a] = axisWord(*this, st.w, a, st.unit());
    s.g92_saved = s.g92;
    s.g92_applied = true;
    s.current = toProgram(s, machine);
  } else {
    if (g == 921) s.g92_saved = AxisValues{};
    if (g == 923) {
      if (params_)
        for (int a = 0; a < kAxisCount; ++a) s.g92_saved[a] = params_->get(5211 + a);
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
  AxisValues& stored = second ? s.g30 : s.g28;
  if (params_)
    for (int a = 0; a < kAxisCount; ++a) stored[a] = params_->get((second ? 5181 : 5161) + a);
  // As LinuxCNC does, the stored point is taken into the program frame whole
  // and the named axes are picked there: under a G10 L2 R rotation an axis left
  // out keeps its program value, not its machine value.
  const AxisValues stored_program = toProgram(s, stored);
  AxisValues target = middle;
  const bool all = !st.w.hasAxis();
  for (int a = 0; a < kAxisCount; ++a)
    if (all || st.w.has(kAxisLetters[a])) target[a] = stored_program[a];
  emitStraight(st, MotionType::kRapid, target, none);
}

}  // namespace mdhd::gcode

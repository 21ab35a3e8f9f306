// LinuxCNC's predefined read-only named parameters (#<_x>, #<_metric>, ...),
// answered from the committed state.
#include <cstring>
#include <string_view>

#include "sim/gcode/block_executor.h"

namespace mdhd::gcode {
namespace {

double flag(bool b) {
  return b ? 1.0 : 0.0;
}

int compCode(const InterpState& s) {
  if (s.comp_side == CompSide::kOff) return 400;
  return s.comp_side == CompSide::kLeft ? 410 : 420;
}

int coordCode(int index) {
  return index < 6 ? 540 + 10 * index : 591 + (index - 6);
}

}  // namespace

bool BlockExecutor::predefined(std::string_view name, double& v) const {
  if (!name.empty() && name.front() == '_') name.remove_prefix(1);
  const InterpState& s = state_;
  const double unit = s.inch ? kMmPerInch : 1.0;
  for (int a = 0; a < kAxisCount; ++a) {
    const char lower = static_cast<char>(kAxisLetters[a] - 'A' + 'a');
    const bool rotary = a >= kA && a <= kC;
    if (name.size() == 1 && name[0] == lower) {
      v = rotary ? s.current[a] : s.current[a] / unit;
      return true;
    }
    if (name.size() == 5 && name.substr(0, 4) == "abs_" && name[4] == lower) {
      const AxisValues m = toMachine(s, s.current);
      v = rotary ? m[a] : m[a] / unit;
      return true;
    }
  }
  struct Entry {
    const char* name;
    double value;
  };
  const Entry entries[] = {
      {"vmajor", 2.9},  // rs274 2.9.0: 2.9 and 0,
      {"vminor", 0.0},
      {"motion_mode", static_cast<double>(s.motion)},
      {"plane", s.plane == Plane::kXY ? 170.0 : (s.plane == Plane::kXZ ? 180.0 : 190.0)},
      {"ccomp", static_cast<double>(compCode(s))},
      {"metric", flag(!s.inch)},
      {"imperial", flag(s.inch)},
      {"absolute", flag(!s.incremental)},
      {"incremental", flag(s.incremental)},
      {"inverse_time", flag(s.feed_mode == FeedMode::kInverseTime)},
      {"units_per_minute", flag(s.feed_mode == FeedMode::kUnitsPerMinute)},
      {"units_per_rev", flag(s.feed_mode == FeedMode::kUnitsPerRevolution)},
      {"coord_system", static_cast<double>(coordCode(s.coord_system))},
      {"tool_offset", flag(s.tool_length_mode != 490)},
      {"retract_r_plane", flag(s.retract_to_r)},
      {"retract_old_z", flag(!s.retract_to_r)},
      {"spindle_rpm_mode", 1.0},
      {"spindle_css_mode", 0.0},
      {"ijk_absolute_mode", flag(s.arc_absolute)},
      {"lathe_diameter_mode", 0.0},
      {"lathe_radius_mode", 1.0},
      {"spindle_on", flag(s.spindle != SpindleState::kOff)},
      {"spindle_cw", flag(s.spindle == SpindleState::kClockwise)},
      {"mist", flag(s.mist)},
      {"flood", flag(s.flood)},
      {"speed_override", flag(s.speed_override)},
      {"feed_override", flag(s.feed_override)},
      {"adaptive_feed", flag(s.adaptive_feed)},
      {"feed_hold", flag(s.feed_hold)},
      {"feed", s.feed_word},
      {"rpm", s.speed},
      {"current_tool", static_cast<double>(s.tool)},
      {"current_pocket", static_cast<double>(s.tool)},
      {"selected_tool", static_cast<double>(s.selected_tool)},
      {"selected_pocket", static_cast<double>(s.selected_tool)},
      {"task", 0.0},
      {"remap_level", 0.0},
  };
  for (const Entry& e : entries) {
    if (name == e.name) {
      v = e.value;
      return true;
    }
  }
  return false;
}

}  // namespace mdhd::gcode

#pragma once
// What a check of a job says (job-format.md section 5) as plain data: the
// verdict, one entry per collision episode, statistics and the stock's own
// figures. The JSON form lives in protocol/report_json.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/gcode/motion.h"
#include "sim/mdh/stats.h"

namespace mdhd::check {

enum class Status { kClean, kCollisions, kError };

enum class CollisionType {
  kRapidIntoStock,  // the cutter removed material during G0
  kShankContact,    // the shank touched material (removes nothing)
  kHolderContact,   // the holder touched material (removes nothing)
  kFixtureContact,  // cutter, shank or holder inside a fixture
  kSpindleOffCut,   // the cutter removed material with the spindle stopped
  kAxisLimit,       // a joint beyond its limits along the path
};

// Which part of the tool a contact is about.
enum class ToolPartName { kCutter, kShank, kHolder, kNone };

std::string_view statusName(Status s);
std::string_view collisionTypeName(CollisionType t);
std::string_view toolPartName(ToolPartName p);

struct Collision {
  CollisionType type = CollisionType::kRapidIntoStock;
  std::string file;   // empty: the main program
  int line = 0;       // first line of the episode
  std::string block;  // that block's text
  int tool = 0;
  glm::dvec3 position{0.0};    // tool tip in W at first contact
  gcode::AxisValues joints{};  // joint values there
  double depth = 0.0;  // deepest penetration over the episode, mm (axis_limit: mm or deg beyond)
  int last_line = 0;   // line where the episode was last seen
  ToolPartName part = ToolPartName::kNone;  // fixture_contact: which part; shank/holder: itself
  int fixture = -1;                         // fixture_contact: index into the job's fixtures
  std::string axis;                         // axis_limit: the joint's name
  // Where on the first motion's path (0..1) the episode began: the share of that
  // motion done before contact (a look-ahead's time to contact). Not in the JSON.
  double path_s = 0.0;
};

struct MoveCounts {
  std::int64_t rapid = 0;
  std::int64_t feed = 0;
  std::int64_t arc = 0;
  std::int64_t total() const { return rapid + feed + arc; }
};

struct ToolUse {
  int tool = 0;
  double cutting_time_s = 0.0;  // feed moves that removed material
  double removed_volume_mm3 = 0.0;
};

struct RunStats {
  std::int64_t blocks = 0;
  MoveCounts moves;
  std::int64_t steps = 0;     // in-between steps (swept volumes cut)
  double path_length = 0.0;   // tool tip in W, mm
  double cycle_time_s = 0.0;  // from feeds, rapid rate, dwells
  double stock_volume_mm3 = 0.0;
  double removed_volume_mm3 = 0.0;
  double final_volume_mm3 = 0.0;
  std::vector<ToolUse> tools;  // in order of first use
};

struct OverhangStats {
  std::int64_t events = 0;
  std::optional<int> first_line;
  std::int64_t cells_not_plus_z = 0;
  double area_mm2 = 0.0;
};

struct Timing {
  double total_ms = 0.0;
  double load_ms = 0.0;    // job and schema (filled by the runner)
  double cut_ms = 0.0;     // Stock::cut
  double probe_ms = 0.0;   // shank, holder, fixture and rapid probes, depths
  double finish_ms = 0.0;  // volume, area and statistics at the end
};

// Why a job could not be checked: a field of the job, or a place in the program.
struct ReportError {
  std::string message;
  std::string field;  // job problems ("tools[0].diameter"); empty for program problems
  std::string file;   // program problems: empty for the main program
  int line = 0;       // program problems: 1-based, 0 when not about a line
  int column = 0;
  std::string block;
};

struct Report {
  Status status = Status::kClean;
  std::optional<ReportError> error;
  std::vector<Collision> collisions;
  RunStats stats;
  mdh::Stats mdh;
  OverhangStats overhang;
  Timing timing;
  double grid_spacing = 0.0;  // mm, 1 / density
  bool cancelled = false;
};

}  // namespace mdhd::check

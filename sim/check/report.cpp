#include "sim/check/report.h"

namespace mdhd::check {

std::string_view statusName(Status s) {
  switch (s) {
    case Status::kClean:
      return "clean";
    case Status::kCollisions:
      return "collisions";
    case Status::kError:
      return "error";
  }
  return "error";
}

std::string_view collisionTypeName(CollisionType t) {
  switch (t) {
    case CollisionType::kRapidIntoStock:
      return "rapid_into_stock";
    case CollisionType::kShankContact:
      return "shank_contact";
    case CollisionType::kHolderContact:
      return "holder_contact";
    case CollisionType::kFixtureContact:
      return "fixture_contact";
    case CollisionType::kSpindleOffCut:
      return "spindle_off_cut";
    case CollisionType::kAxisLimit:
      return "axis_limit";
  }
  return "?";
}

std::string_view toolPartName(ToolPartName p) {
  switch (p) {
    case ToolPartName::kCutter:
      return "cutter";
    case ToolPartName::kShank:
      return "shank";
    case ToolPartName::kHolder:
      return "holder";
    case ToolPartName::kNone:
      return "";
  }
  return "";
}

}  // namespace mdhd::check

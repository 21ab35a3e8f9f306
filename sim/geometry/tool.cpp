#include "sim/geometry/tool.h"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace mdhd::geom {

namespace {

constexpr struct {
  ToolShape shape;
  std::string_view name;
} kShapeNames[] = {{ToolShape::kFlat, "flat"},
                   {ToolShape::kBall, "ball"},
                   {ToolShape::kBull, "bull"},
                   {ToolShape::kDrill, "drill"}};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

std::optional<ToolProblem> checkSizes(const Tool& t) {
  if (t.number < 1) return ToolProblem{"number", "must be an integer >= 1"};
  if (!positive(t.diameter)) return ToolProblem{"diameter", "must be > 0"};
  if (!positive(t.flute_length)) return ToolProblem{"flute_length", "must be > 0"};
  if (!positive(t.length)) return ToolProblem{"length", "must be > 0"};
  if (!positive(t.shank_diameter)) return ToolProblem{"shank_diameter", "must be > 0"};
  if (!std::isfinite(t.corner_radius) || t.corner_radius < 0.0)
    return ToolProblem{"corner_radius", "must be >= 0"};
  if (!std::isfinite(t.tip_angle) || t.tip_angle < 0.0)
    return ToolProblem{"tip_angle", "must be >= 0"};
  for (size_t i = 0; i < t.holder.size(); ++i) {
    const std::string at = "holder[" + std::to_string(i) + "].";
    if (!positive(t.holder[i].diameter)) return ToolProblem{at + "diameter", "must be > 0"};
    if (!positive(t.holder[i].length)) return ToolProblem{at + "length", "must be > 0"};
  }
  return std::nullopt;
}

std::optional<ToolProblem> checkShape(const Tool& t) {
  switch (t.shape) {
    case ToolShape::kBull:
      if (t.corner_radius <= 0.0) return ToolProblem{"corner_radius", "must be > 0 for a bull"};
      if (t.corner_radius > t.radius())
        return ToolProblem{"corner_radius", "must be <= diameter/2"};
      break;
    case ToolShape::kDrill:
      if (t.tip_angle <= 0.0 || t.tip_angle >= 180.0)
        return ToolProblem{"tip_angle", "must be in (0, 180) degrees for a drill"};
      break;
    default:
      break;
  }
  // A shape's own size only matters where it is used; elsewhere 0 is the norm.
  if (t.shape != ToolShape::kBull && t.corner_radius != 0.0)
    return ToolProblem{"corner_radius", "is only used by shape bull: must be 0 or absent"};
  if (t.shape != ToolShape::kDrill && t.tip_angle != 0.0)
    return ToolProblem{"tip_angle", "is only used by shape drill: must be 0 or absent"};
  return std::nullopt;
}

std::optional<ToolProblem> checkLengths(const Tool& t) {
  if (t.flute_length > t.length)
    return ToolProblem{"flute_length", "must be <= length (" + number(t.length) + ")"};
  if (t.flute_length < t.tipHeight())
    return ToolProblem{"flute_length",
                       "must be >= the height of the tip shape (" + number(t.tipHeight()) + ")"};
  double stack = 0.0;
  for (const HolderSection& h : t.holder) stack += h.length;
  if (stack > t.length)
    return ToolProblem{"holder", "is longer (" + number(stack) + ") than the tool length (" +
                                     number(t.length) + ")"};
  if (stack + t.flute_length > t.length)
    return ToolProblem{"holder", "reaches into the flutes: holder lengths (" + number(stack) +
                                     ") + flute_length must be <= length"};
  return std::nullopt;
}

}  // namespace

std::optional<ToolShape> toolShapeFromName(std::string_view name) {
  for (const auto& s : kShapeNames)
    if (s.name == name) return s.shape;
  return std::nullopt;
}

std::string_view toolShapeName(ToolShape shape) {
  for (const auto& s : kShapeNames)
    if (s.shape == shape) return s.name;
  return "?";
}

double Tool::holderBottom() const {
  double stack = 0.0;
  for (const HolderSection& h : holder) stack += h.length;
  return length - stack;
}

double Tool::tipHeight() const {
  switch (shape) {
    case ToolShape::kBall:
      return radius();
    case ToolShape::kBull:
      return corner_radius;
    case ToolShape::kDrill:
      return radius() / std::tan(tip_angle * std::numbers::pi / 360.0);
    default:
      return 0.0;
  }
}

std::optional<ToolProblem> validateTool(const Tool& tool) {
  if (auto p = checkSizes(tool)) return p;
  if (auto p = checkShape(tool)) return p;
  return checkLengths(tool);
}

}  // namespace mdhd::geom

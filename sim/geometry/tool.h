#pragma once
// A milling tool as the job describes it (job-format.md section 3), and its checks.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mdhd::geom {

enum class ToolShape { kFlat, kBall, kBull, kDrill };

// Name as the job writes it ("flat", "ball", "bull", "drill"); nullopt if unknown.
std::optional<ToolShape> toolShapeFromName(std::string_view name);
std::string_view toolShapeName(ToolShape shape);

// One cylinder of the holder stack, listed from the gauge point downwards.
struct HolderSection {
  double diameter = 0.0;
  double length = 0.0;

  bool operator==(const HolderSection&) const = default;
};

struct Tool {
  int number = 0;
  ToolShape shape = ToolShape::kFlat;
  double diameter = 0.0;
  double flute_length = 0.0;  // cutting part, from the tip upwards
  double length = 0.0;        // gauge point to tip
  double shank_diameter = 0.0;
  double corner_radius = 0.0;  // bull only
  double tip_angle = 0.0;      // drill only: included angle of the cone, degrees
  std::vector<HolderSection> holder;

  double radius() const { return diameter / 2.0; }
  // Height above the tip where the holder starts (the shank ends there).
  double holderBottom() const;
  // Height of the curved or pointed bottom: R (ball), corner_radius (bull), the cone (drill).
  double tipHeight() const;

  bool operator==(const Tool&) const = default;
};

// What is wrong with a tool: the field as the job names it ("corner_radius",
// "holder[1].length") and a message saying what it must be.
struct ToolProblem {
  std::string field;
  std::string message;
};

// The first problem found, or nullopt if the tool describes a buildable solid.
std::optional<ToolProblem> validateTool(const Tool& tool);

}  // namespace mdhd::geom

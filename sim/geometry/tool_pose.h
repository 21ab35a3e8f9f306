#pragma once
// Where a tool is: its tip and its axis (unit, from the tip towards the spindle), in
// the workpiece frame W. The tool is a body of revolution, so this is all of it.
#include <glm/vec3.hpp>

namespace mdhd::geom {

struct ToolPose {
  glm::dvec3 tip{0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};
};

}  // namespace mdhd::geom

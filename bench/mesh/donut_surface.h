#pragma once
// The design surface of the thesis's figure 6.13 (table 6.8): a ball tool of
// radius R tilted by theta towards a vertical axis, its tip on a circle of
// radius R_maj about that axis, turned 360 degrees. Closest-point error of a
// sample point by equations 6.1 to 6.7: the capsule whose medial axis lies in
// the plane of the point and the rotation axis.
#include <algorithm>
#include <cmath>

#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool.h"
#include "sim/geometry/tool_part.h"
#include "sim/mdh/stock.h"

namespace mdhd::mesh::bench {

struct Donut {
  double radius = 0.15;                 // R: tool and torus minor radius, mm
  double tiltDegrees = 25.0;            // theta
  double majorRadius = 1.69;            // R_maj
  glm::dvec3 centre{2.0, 2.0, 0.6748};  // P_T, on the rotation axis

  double tilt() const { return tiltDegrees * 3.14159265358979323846 / 180.0; }
  // The tool at turn angle phi (radians): its ball's centre (the start P_A of
  // the capsule's medial axis, on the torus's centre circle), its tip (the
  // lowest point along the axis, where sim/geometry puts a tool) and its axis
  // (tip towards the spindle).
  glm::dvec3 ballCentre(double phi) const {
    return centre + majorRadius * glm::dvec3(std::cos(phi), std::sin(phi), 0.0);
  }
  glm::dvec3 tip(double phi) const { return ballCentre(phi) - radius * axis(phi); }
  glm::dvec3 axis(double phi) const {
    return glm::dvec3(-std::sin(tilt()) * std::cos(phi), -std::sin(tilt()) * std::sin(phi),
                      std::cos(tilt()));
  }

  // Equations 6.1 to 6.7.
  double error(const glm::dvec3& ps) const {
    glm::dvec3 d(ps.x - centre.x, ps.y - centre.y, 0.0);
    const double len = glm::length(d);
    d = len > 0.0 ? d / len : glm::dvec3(1, 0, 0);                                    // (6.5)
    const glm::dvec3 pa = centre + majorRadius * d;                                   // (6.6)
    const glm::dvec3 pb = centre + glm::dvec3(0, 0, majorRadius / std::tan(tilt()));  // (6.7)
    const glm::dvec3 m = pb - pa;                                                     // (6.2)
    const double t = glm::dot(ps - pa, m) / glm::dot(m, m);                           // (6.3)
    const glm::dvec3 pc = t > 0.0 ? pa + t * m : pa;                                  // (6.4)
    return std::abs(glm::length(ps - pc) - radius);                                   // (6.1)
  }
};

// The ball tool of table 6.8 (0.3 mm, shank as thick).
inline geom::ToolPart donutTool(const Donut& d) {
  geom::Tool tool;
  tool.number = 1;
  tool.shape = geom::ToolShape::kBall;
  tool.diameter = 2 * d.radius;
  tool.flute_length = 6;
  tool.length = 20;
  tool.shank_diameter = 2 * d.radius;
  return geom::makeToolPart(tool, geom::ToolPartKind::kCutter);
}

// The full turn as `steps` cuts (in-between steps), each a chain of
// `substeps` straight segments along the arc.
inline void cutDonut(mdh::Stock& stock, const Donut& d, int steps, int substeps) {
  const geom::ToolPart part = donutTool(d);
  stock.setToolRadius(d.radius);
  const double turn = 2 * 3.14159265358979323846;
  std::vector<geom::ToolPose> poses;
  for (int k = 0; k < steps; ++k) {
    poses.clear();
    for (int s = 0; s <= substeps; ++s) {
      const double phi = turn * (k + double(s) / substeps) / steps;
      poses.push_back({d.tip(phi), d.axis(phi)});
    }
    stock.cut(geom::SweptVolume(part, poses), d.axis(turn * (k + 0.5) / steps));
  }
}

}  // namespace mdhd::mesh::bench

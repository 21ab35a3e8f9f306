#pragma once
// The tool's parts in its own frame: tip at the origin, axis +z towards the spindle.
// Every part is a union of convex bodies of revolution; every body is a stack of
// pieces, each a quadric of revolution cut by two planes, which is what the swept
// volume can intersect with a line in closed form.
#include <vector>

#include "sim/geometry/tool.h"

namespace mdhd::geom {

// {p : z0 <= z <= z1, x^2 + y^2 <= alpha + beta*z + gamma*z^2}, convex on [z0, z1].
struct RevolvedPiece {
  double z0 = 0.0;
  double z1 = 0.0;
  double alpha = 0.0;
  double beta = 0.0;
  double gamma = 0.0;
  // The profile's shape for signed distances: a segment from (r0, z0) to (r1, z1),
  // or a circular arc about (0, centre) when `sphere` is set.
  bool sphere = false;
  double centre = 0.0;
  double r0 = 0.0;
  double r1 = 0.0;

  double radiusAt(double z) const;
  double maxRadius() const;
};

RevolvedPiece cylinderPiece(double z0, double z1, double radius);
// Radius r0 at z0 to r1 at z1 (both >= 0): cylinders, cones and frustums.
RevolvedPiece frustumPiece(double z0, double z1, double r0, double r1);
// The zone z0 <= z <= z1 of a ball of `radius` centred on the axis at `centre`.
RevolvedPiece spherePiece(double centre, double radius, double z0, double z1);

// Whether `above` continues `below` (stacked on it) without a crease: same radius and
// same slope where they meet (a ball's zone under its cylinder), so no extreme of a
// section lies on their common plane that is not also one of either piece's own.
bool smoothJoin(const RevolvedPiece& below, const RevolvedPiece& above);

// A convex solid of revolution: pieces stacked bottom to top, touching.
struct ConvexBody {
  std::vector<RevolvedPiece> pieces;

  double bottom() const { return pieces.front().z0; }
  double top() const { return pieces.back().z1; }
  double radiusAt(double z) const;  // 0 outside [bottom, top]
};

enum class ToolPartKind { kCutter, kShank, kHolder };

struct ToolPart {
  ToolPartKind kind = ToolPartKind::kCutter;
  std::vector<ConvexBody> bodies;  // empty when the part has no extent (no holder)

  // Distance of the farthest point from the axis point at `height` above the tip:
  // what a turn of the axis about that point moves most.
  double reach(double height = 0.0) const;
  // The widest radius: no point lies deeper inside the part than that (the ball about
  // it must fit in the part's section through its centre).
  double maxRadius() const;
  // Half-way between the lowest and highest point: the pivot with the least reach.
  double centreHeight() const;
  // How far the part's surface moves at most (Hausdorff distance) per radian its axis
  // turns about the point at `height` on it: the rate of its support function, at a
  // point the part of its distance from the pivot square to the normal. A ball zone
  // moves as its centre does, a side by |z + r r'| / sqrt(1 + r'^2) (z above the pivot),
  // a flat face by its radius, a rim or crease by its whole distance. <= reach(height).
  double turnRate(double height) const;
  // The height on the axis with the least turnRate: the pivot SweptVolume::between
  // turns the part about (a ball cutter's lies above its centre height, where the
  // flutes' top rim and the ball's centre move alike).
  double turnPivot() const;
  bool empty() const { return bodies.empty(); }
};

// The bull's torus corner is a stack of frustums through points of the true arc: the
// solid lies inside the true tool and at most `corner_tolerance` (mm) below its surface.
inline constexpr double kDefaultCornerTolerance = 1e-3;

// The part of a valid tool (see validateTool).
// Throws std::invalid_argument with validateTool's problem for an invalid tool.
ToolPart makeToolPart(const Tool& tool, ToolPartKind kind,
                      double corner_tolerance = kDefaultCornerTolerance);

}  // namespace mdhd::geom

#pragma once
// The volume a tool part sweeps between poses, as a LineSolid for the stock.
//
// A move with a constant axis is a translation, and its sweep is represented exactly:
// every convex body of the part is Minkowski-summed with the segment and cut with the
// grid line in closed form (section_solver.h). A move that turns the axis becomes a
// union of translations, each with one in-between pose's axis, off from the true
// sweep by at most errorBound().
#include <span>
#include <vector>

#include "sim/geometry/axial_sweep.h"
#include "sim/geometry/cross_sweep.h"
#include "sim/geometry/line_solid.h"
#include "sim/geometry/tool_part.h"
#include "sim/geometry/tool_pose.h"

namespace mdhd::geom {

// One translational sweep: the part at `axis` with its tip moving from `from` to `to`.
struct Translation {
  glm::dvec3 from{0.0};
  glm::dvec3 to{0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};
};

// How SweptVolume::between places the held axes of a turning move. kExact: n + 1
// translations, the two end poses held exactly over half a segment each. kMidpoints:
// n translations, each segment holding its middle pose's axis: the same errorBound()
// with one translation fewer (a third fewer for n = 2), the end poses then only within
// errorBound() (a move's last step and the next move's first overlap there anyway).
enum class SweepEnds { kExact, kMidpoints };

class SweptVolume final : public LineSolid {
 public:
  // The part moving from `a` to `b`: tip on the segment, axis along the great circle
  // (slerp). steps > 0: that many equal segments; steps == 0: as many as keep
  // errorBound() <= tolerance (one for a pure translation). The pose at j/n holds its
  // axis from (j - 1/2)/n to (j + 1/2)/n while the part's pivot (turnPivot) runs on
  // the chord of its path: the bound is the turn of half a segment at the part's
  // turnRate about the pivot plus the chord's sagitta. The end poses are exact (`ends`
  // kExact; kMidpoints: one translation fewer, the ends within the bound). Throws
  // std::invalid_argument for a non-finite pose, a zero axis, opposite axes (no
  // unique great circle: split the move) or a tolerance that is not > 0 when needed.
  static SweptVolume between(const ToolPart& part, const ToolPose& a, const ToolPose& b, int steps,
                             double tolerance, SweepEnds ends = SweepEnds::kExact);
  // The union of the part's sweeps from each pose's tip to the next's, the axis held
  // over each segment: what SweptVolume::between gives each pair (translations of
  // the same ends), in one solid. Runs along one line merge as in between(). Throws
  // as between() does, and for fewer than two poses.
  static SweptVolume chainOfTranslations(const ToolPart& part, std::span<const ToolPose> poses);
  // The part standing at one pose (a stamp).
  static SweptVolume at(const ToolPart& part, const ToolPose& pose);
  // Through a chain of poses (at least one), tips joined by segments, each pose's axis
  // held over the half-segments next to it (so every pose is exact); runs with one
  // axis on one line merge. errorBound() is the turn of half a segment at the reach
  // from the tip, against the axis slerped between consecutive poses.
  SweptVolume(const ToolPart& part, std::span<const ToolPose> poses);

  Aabb bounds() const override { return bounds_; }
  // Piece by piece, each clipped as slab_bounds.h says, where some body leans (its
  // axis on no grid axis); otherwise the box clipped, which is then as tight.
  Aabb boundsIn(const Aabb& box) const override;
  // Const and allocation-free beyond `out`, so any number of threads may call it.
  // Ends where the line crosses the surface are good to ~1e-12 of the part's size;
  // where it only grazes it (a tangent, a cone's apex) to ~1e-8. Lines that only touch
  // the solid (zero length) give nothing. Cost grows with translations().size().
  // Translations whose axis is a grid axis answer lines along it (axial_sweep.h) and
  // square to it (cross_sweep.h) in closed form; every other line and body goes
  // through the general solver (section_solver.h).
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override;
  // The same answers (swept_rows.cpp). When every body stands on the lines' axis (a
  // 3-axis tool's z columns), body by body over the row: each body solves the lines
  // its box holds in one branch-free pass (axialExtentRow); when every body is square
  // to it (its x and y lines), as linesIntervals; otherwise line by line.
  void rowIntervals(int axis, std::span<const double> us, double v, std::vector<Interval>& out,
                    std::span<std::size_t> ends) const override;
  bool rowsPay(int axis) const override {
    return axis >= 0 && axis <= 2 && (rowKernel_[axis] || rowCross_[axis]);
  }
  // The same answers. When every body is square to the lines (a 3-axis tool's x and
  // y lines), body by body, each piece over the lines it may meet in one
  // branch-free pass (crossExtentRow); otherwise line by line.
  void linesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                      std::vector<Interval>& out, std::span<std::size_t> ends) const override;
  bool linesPay(int axis) const override { return axis >= 0 && axis <= 2 && rowCross_[axis]; }
  // Every body on one grid axis, translated: the coordinates where each body's
  // section is its widest disk at every point of its move (profile from riseTop to
  // top), intersected over the bodies that reach there.
  bool prismBand(int& axis, double& lo, double& hi) const override;
  // The same through the general solver for every body and line: the reference the
  // closed forms are tested and benchmarked against.
  void generalLineIntervals(int axis, double u, double v, std::vector<Interval>& out) const;

  // The translational sweeps this is exactly the union of.
  const std::vector<Translation>& translations() const { return translations_; }
  // Bound on the distance between this and the sweep with the axis slerped between
  // consecutive poses (0 when the axis never turns).
  double errorBound() const { return errorBound_; }
  bool empty() const { return bodies_.empty(); }

 private:
  struct AxisTerms {
    double ze = 0, zd = 0, re2 = 0, rerd = 0, rd2 = 0;
  };
  struct SweptPiece {
    PieceQuadric q;
    Aabb box;
    bool smoothBelow = false, smoothAbove = false;  // joins of the body's stack
    // A ball's lower half under a cylinder of its radius that covers its upper half:
    // swept, the whole ball's capsule is exact for the body (capsule_line.h).
    bool capsule = false;
    double centre = 0.0, radius = 0.0;  // the ball's centre height above the tip
    double maxRadius = 0.0;             // the piece's widest disk
  };
  struct SweptBody {
    Aabb box;
    glm::dvec3 tip{0.0};
    glm::dvec3 axis{0.0};
    glm::dvec3 dir{0.0};  // unit direction of the move (0 for a stamp)
    double length = 0.0;
    double linearTol = 0.0;
    double quadricTol = 0.0;
    AxisTerms terms[3];
    int pieceBegin = 0;
    int pieceEnd = 0;
    // Closed forms: lines along `alongAxis` (the tool's axis, -1 if it is no grid
    // axis or the body has no profile) and square to the axis (crossing[a]).
    int alongAxis = -1;
    int profile = -1;
    AxialMove along;
    bool crossing[3] = {false, false, false};
    CrossMove cross[3];
    glm::dvec3 crossNormal[3];
  };

  SweptVolume(const ToolPart& part, const std::vector<Translation>& moves, double errorBound);
  void build(const ToolPart& part, const std::vector<Translation>& moves);
  void addTranslation(const ToolPart& part, const std::vector<int>& profileOf,
                      const Translation& tr);
  struct LineFrame;
  void intervals(int axis, double u, double v, bool general, std::vector<Interval>& out) const;
  // `general`: the section solver's candidate enumeration (the reference) instead of
  // its band form.
  // Heights [lo, hi] on a body's axis (on grid axis `axis`) as coordinates on that axis.
  static Interval axialInterval(const SweptBody& body, int axis, double lo, double hi);
  bool bodyInterval(const SweptBody& body, int axis, double u, double v, bool general,
                    Interval& out) const;
  bool crossBodyInterval(const SweptBody& body, int axis, double u, double v, Interval& out) const;
  void crossLinesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                           std::vector<Interval>& out, std::span<std::size_t> ends) const;
  bool pieceExtent(const SweptBody& body, const SweptPiece& p, const LineFrame& f, bool general,
                   double& lo, double& hi) const;

  std::vector<Translation> translations_;
  std::vector<SweptBody> bodies_;
  std::vector<SweptPiece> pieces_;
  std::vector<AxialProfile> profiles_;
  Aabb bounds_;
  double errorBound_ = 0.0;
  bool rowKernel_[3] = {false, false, false};  // every body solved by axialExtentRow on axis a
  bool rowCross_[3] = {false, false, false};   // every body square to axis a (crossExtentRow)
  bool leans_ = false;                         // some body's axis on no grid axis
};

// How many equal segments SweptVolume::between uses for these arguments.
int sweepSegments(const ToolPart& part, const ToolPose& a, const ToolPose& b, int steps,
                  double tolerance);

}  // namespace mdhd::geom

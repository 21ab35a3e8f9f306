#include "sim/check/contact_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "sim/geometry/signed_distance.h"

namespace mdhd::check {
namespace {

constexpr int kGoldenIterations = 28;
constexpr double kInvPhi = 0.6180339887498949;

// The point in the tool frame of a pose: bodies of revolution only need (r, 0, z).
glm::dvec3 toolFrame(const glm::dvec3& p, const glm::dvec3& tip, const glm::dvec3& axis) {
  const glm::dvec3 d = p - tip;
  const double z = glm::dot(d, axis);
  const glm::dvec3 radial = d - z * axis;
  return {std::sqrt(glm::dot(radial, radial)), 0.0, z};
}

double bodyAlong(const geom::ConvexBody& body, const geom::Translation& tr, const glm::dvec3& p) {
  const glm::dvec3 move = tr.to - tr.from;
  auto f = [&](double t) {
    return geom::signedDistance(body, toolFrame(p, tr.from + t * move, tr.axis));
  };
  if (glm::dot(move, move) == 0.0) return f(0.0);
  double a = 0.0, b = 1.0;
  double c = b - kInvPhi * (b - a), d = a + kInvPhi * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < kGoldenIterations; ++i) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kInvPhi * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kInvPhi * (b - a);
      fd = f(d);
    }
  }
  return std::min({fc, fd, f(0.0), f(1.0)});
}

void overlaps(const std::vector<geom::Interval>& a, const std::vector<geom::Interval>& b,
              std::vector<geom::Interval>& out) {
  out.clear();
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const double lo = std::max(a[i].lo, b[j].lo), hi = std::min(a[i].hi, b[j].hi);
    if (lo < hi) out.push_back({lo, hi});
    if (a[i].hi < b[j].hi)
      ++i;
    else
      ++j;
  }
}

}  // namespace

geom::Aabb intersect(const geom::Aabb& a, const geom::Aabb& b) {
  return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

bool isEmpty(const geom::Aabb& b) {
  return !(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z);
}

double sweptSignedDistance(const geom::SweptVolume& sweep, const geom::ToolPart& part,
                           const glm::dvec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const geom::Translation& tr : sweep.translations())
    for (const geom::ConvexBody& body : part.bodies) best = std::min(best, bodyAlong(body, tr, p));
  return best;
}

Penetration penetration(const geom::SweptVolume& sweep, const geom::ToolPart& part,
                        const geom::Aabb& within, const LineGrid& grid,
                        const MaterialLine& material, bool measure, double enough) {
  Penetration out;
  const geom::Aabb box = intersect(sweep.bounds(), within);
  if (isEmpty(box) || part.empty()) return out;
  const int x0 =
      std::max(grid.ix_min, static_cast<int>(std::ceil((box.lo.x - grid.origin_x) / grid.h)));
  const int x1 =
      std::min(grid.ix_max, static_cast<int>(std::floor((box.hi.x - grid.origin_x) / grid.h)));
  const int y0 =
      std::max(grid.iy_min, static_cast<int>(std::ceil((box.lo.y - grid.origin_y) / grid.h)));
  const int y1 =
      std::min(grid.iy_max, static_cast<int>(std::floor((box.hi.y - grid.origin_y) / grid.h)));
  if (x0 > x1 || y0 > y1) return out;
  // Each axis its own stride: one shared by both skipped the middle line of a thin part's
  // long sweep (a 0.15 mm shank dragged 10 mm at 20 points/mm: every 4th of its 3 lines
  // across, the deepest never sampled and the contact lost).
  const auto strideOf = [](int lines) {
    return std::max(1, (lines + kMaxDepthLinesPerAxis) / kMaxDepthLinesPerAxis);
  };
  const int sx = strideOf(x1 - x0), sy = strideOf(y1 - y0);
  // Strided lines run through the box's middle line, where a part is often deepest.
  const int xs = x0 + ((x1 - x0) / 2) % sx, ys = y0 + ((y1 - y0) / 2) % sy;
  // Samples one overlap of line (x, y); true once a sample is deeper than `enough`.
  const auto sample = [&](double x, double y, double lo, double hi) {
    const int n = std::clamp(static_cast<int>(std::ceil((hi - lo) / grid.h)) + 1, 2,
                             kMaxDepthSamplesPerOverlap);
    for (int k = 0; k < n; ++k) {
      const glm::dvec3 p{x, y, lo + (hi - lo) * k / (n - 1)};
      const double depth = -sweptSignedDistance(sweep, part, p);
      if (depth > out.depth) {
        out.depth = depth;
        out.deepest = p;
        if (depth > enough) return true;
      }
    }
    return false;
  };
  // No point of an overlap lies deeper in the sweep than half the sweep's own interval
  // on the line allows (its ends are the sweep's boundary): overlaps are sampled in
  // the order of that bound, and those whose bound cannot beat the depth found by more
  // than h/4 are not sampled at all (a holder dragged sideways through the stock
  // samples a few lines instead of thousands). The first is always sampled: with nothing
  // found yet the rule skipped every overlap shallower than h/4, so a contact tolerance
  // set below h/4 lost the contacts between it and h/4 (0.03 mm at density 5 with a
  // tolerance of 0.01 ran `clean` until session 23).
  struct Found {
    double bound, x, y, lo, hi;
  };
  std::vector<Found> found;
  std::vector<geom::Interval> mat, tool, both;
  for (int iy = ys; iy <= y1; iy += sy) {
    for (int ix = xs; ix <= x1; ix += sx) {
      const double x = grid.origin_x + ix * grid.h, y = grid.origin_y + iy * grid.h;
      tool.clear();
      sweep.lineIntervals(2, x, y, tool);
      if (tool.empty()) continue;
      mat.clear();
      material(ix, iy, x, y, mat);
      overlaps(mat, tool, both);
      std::size_t t = 0;  // the sweep's interval holding the overlap (both are sorted)
      for (const geom::Interval& o : both) {
        const double lo = std::max(o.lo, box.lo.z), hi = std::min(o.hi, box.hi.z);
        if (!(hi > lo)) continue;
        out.max_overlap = std::max(out.max_overlap, hi - lo);
        if (!measure) continue;
        while (t + 1 < tool.size() && tool[t].hi < lo) ++t;
        const double mid = 0.5 * (tool[t].lo + tool[t].hi);
        const double bound = mid < lo   ? tool[t].hi - lo
                             : mid > hi ? hi - tool[t].lo
                                        : 0.5 * (tool[t].hi - tool[t].lo);
        found.push_back({bound * (1.0 + 1e-12) + 1e-12, x, y, lo, hi});
      }
    }
  }
  std::sort(found.begin(), found.end(),
            [](const Found& a, const Found& b) { return a.bound > b.bound; });
  for (const Found& f : found) {
    if (&f != &found.front() && f.bound <= out.depth + 0.25 * grid.h) break;
    if (sample(f.x, f.y, f.lo, f.hi)) break;
  }
  return out;
}

}  // namespace mdhd::check

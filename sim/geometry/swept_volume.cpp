#include "sim/geometry/swept_volume.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "sim/geometry/capsule_line.h"
#include "sim/geometry/pose_interpolation.h"
#include "sim/geometry/section_solver.h"
#include "sim/geometry/slab_bounds.h"

namespace mdhd::geom {

namespace {

constexpr int kMaxSegments = 100000;

// A coordinate by a run-time index: glm's operator[] is a switch, and the line queries
// index by axis in every test.
inline double coord(const glm::dvec3& v, int i) {
  return glm::value_ptr(v)[i];
}

Aabb emptyBox() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return Aabb{glm::dvec3(inf), glm::dvec3(-inf)};
}

void grow(Aabb& box, const Aabb& other) {
  box.lo = glm::min(box.lo, other.lo);
  box.hi = glm::max(box.hi, other.hi);
}

// Box of a cylinder of `radius` from `base + z0 axis` to `base + z1 axis`: the hull of
// its two end disks, each spanning radius * sqrt(1 - axis_i^2) along coordinate i.
Aabb cylinderBox(const glm::dvec3& base, const glm::dvec3& axis, double z0, double z1,
                 double radius) {
  glm::dvec3 ext;
  for (int i = 0; i < 3; ++i) ext[i] = radius * std::sqrt(std::max(0.0, 1.0 - axis[i] * axis[i]));
  const glm::dvec3 c0 = base + z0 * axis;
  const glm::dvec3 c1 = base + z1 * axis;
  return Aabb{glm::min(c0, c1) - ext, glm::max(c0, c1) + ext};
}

bool collinearContinuation(const Translation& run, const glm::dvec3& next) {
  const glm::dvec3 a = run.to - run.from;
  const glm::dvec3 b = next - run.to;
  const double aa = glm::dot(a, a);
  const double bb = glm::dot(b, b);
  if (aa == 0.0 || bb == 0.0) return true;
  const glm::dvec3 c = glm::cross(a, b);
  return glm::dot(a, b) > 0.0 && glm::dot(c, c) <= 1e-24 * aa * bb;
}

// Sorts out[first, end) by start and merges what overlaps or touches, in place (so
// nothing but `out` is allocated).
[[gnu::always_inline]] inline void mergeFrom(std::vector<Interval>& out, std::size_t first) {
  if (out.size() - first < 2) return;
  std::sort(out.begin() + first, out.end(),
            [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
  std::size_t keep = first;
  for (std::size_t i = first + 1; i < out.size(); ++i) {
    if (out[i].lo <= out[keep].hi)
      out[keep].hi = std::max(out[keep].hi, out[i].hi);
    else
      out[++keep] = out[i];
  }
  out.erase(out.begin() + static_cast<std::ptrdiff_t>(keep + 1), out.end());
}

void checkTolerance(double tolerance) {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("swept volume: tolerance must be > 0 with adaptive steps, got " +
                                std::to_string(tolerance));
}

}  // namespace

namespace {

// The bound of SweptVolume::between with n segments turning th in all: the held axis
// is at most th / 2n from the true one, which moves the surface by at most `rate`
// (ToolPart::turnRate about the pivot) per radian, and the pivot (at `height` on the
// axis) runs on a chord of its arc, off by the sagitta.
double betweenErrorBound(double th, int n, double rate, double height) {
  const double step = th / n;
  return rate * step / 2.0 + std::abs(height) * step * step / 4.0;
}

}  // namespace

int sweepSegments(const ToolPart& part, const ToolPose& a, const ToolPose& b, int steps,
                  double tolerance) {
  if (steps < 0) throw std::invalid_argument("swept volume: steps must be >= 0");
  const ToolPose pa = normalizedPose(a);
  const ToolPose pb = normalizedPose(b);
  const double th = axisAngle(pa.axis, pb.axis);
  if (th > std::acos(-1.0) - 1e-9)
    throw std::invalid_argument(
        "swept volume: opposite tool axes have no unique path between them");
  if (steps > 0) return steps;
  if (th == 0.0) return 1;
  checkTolerance(tolerance);
  const double h = part.turnPivot();
  const double rate = part.turnRate(h);
  // The turn alone needs rate th / 2n <= tolerance; the sagitta adds a little.
  double n = std::max(1.0, std::ceil(rate * th / (2.0 * tolerance)));
  while (n <= kMaxSegments && betweenErrorBound(th, static_cast<int>(n), rate, h) > tolerance)
    n += std::max(1.0, std::floor(n / 64));
  if (!(n <= kMaxSegments))
    throw std::invalid_argument("swept volume: tolerance " + std::to_string(tolerance) +
                                " needs more than " + std::to_string(kMaxSegments) +
                                " steps for this turn of the tool axis");
  return static_cast<int>(n);
}

SweptVolume SweptVolume::between(const ToolPart& part, const ToolPose& a, const ToolPose& b,
                                 int steps, double tolerance, SweepEnds ends) {
  const int n = sweepSegments(part, a, b, steps, tolerance);
  const ToolPose pa = normalizedPose(a);
  const ToolPose pb = normalizedPose(b);
  const double th = axisAngle(pa.axis, pb.axis);
  if (th == 0.0) return SweptVolume(part, {Translation{pa.tip, pb.tip, pa.axis}}, 0.0);
  // Pose j (at j/n) holds its axis from (j - 1/2)/n to (j + 1/2)/n, clamped to [0, 1].
  // Turning about a point up the axis instead of the tip moves the surface about half
  // as far, so half as many steps meet the tolerance; that point's path is an arc
  // that each step replaces by its chord.
  const double h = part.turnPivot();
  auto centre = [&](double f) {
    const ToolPose q = interpolatePose(pa, pb, f);
    return q.tip + h * q.axis;
  };
  std::vector<Translation> moves;
  moves.reserve(n + 1);
  if (ends == SweepEnds::kMidpoints) {
    // Segment j holds the axis at (j + 1/2)/n while the centre runs on its chord.
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 w = interpolatePose(pa, pb, (j + 0.5) / n).axis;
      moves.push_back(
          Translation{centre(double(j) / n) - h * w, centre(double(j + 1) / n) - h * w, w});
    }
    return SweptVolume(part, moves, betweenErrorBound(th, n, part.turnRate(h), h));
  }
  for (int j = 0; j <= n; ++j) {
    const glm::dvec3 w = interpolatePose(pa, pb, double(j) / n).axis;
    const glm::dvec3 from = j == 0 ? pa.tip : centre((j - 0.5) / n) - h * w;
    const glm::dvec3 to = j == n ? pb.tip : centre((j + 0.5) / n) - h * w;
    moves.push_back(Translation{from, to, w});
  }
  return SweptVolume(part, moves, betweenErrorBound(th, n, part.turnRate(h), h));
}

SweptVolume SweptVolume::chainOfTranslations(const ToolPart& part,
                                             std::span<const ToolPose> poses) {
  if (poses.size() < 2) throw std::invalid_argument("swept volume: a chain needs two poses");
  std::vector<Translation> moves;
  moves.reserve(poses.size() - 1);
  ToolPose a = normalizedPose(poses[0]);
  for (std::size_t j = 1; j < poses.size(); ++j) {
    const ToolPose b = normalizedPose(poses[j]);
    if (axisAngle(a.axis, b.axis) != 0.0)
      throw std::invalid_argument("swept volume: a chain of translations turns the tool axis");
    moves.push_back(Translation{a.tip, b.tip, a.axis});
    a = b;
  }
  return SweptVolume(part, moves, 0.0);
}

SweptVolume SweptVolume::at(const ToolPart& part, const ToolPose& pose) {
  return SweptVolume(part, std::span<const ToolPose>(&pose, 1));
}

SweptVolume::SweptVolume(const ToolPart& part, std::span<const ToolPose> poses) {
  if (poses.empty()) throw std::invalid_argument("swept volume: needs at least one pose");
  std::vector<ToolPose> p;
  p.reserve(poses.size());
  for (const ToolPose& q : poses) p.push_back(normalizedPose(q));
  const double reach = part.reach();
  // Pose j holds from the midpoint before it, through its tip, to the midpoint after.
  std::vector<Translation> moves;
  for (size_t j = 0; j < p.size(); ++j) {
    const glm::dvec3 from = j == 0 ? p[j].tip : 0.5 * (p[j - 1].tip + p[j].tip);
    const glm::dvec3 to = j + 1 == p.size() ? p[j].tip : 0.5 * (p[j].tip + p[j + 1].tip);
    moves.push_back(Translation{from, p[j].tip, p[j].axis});
    moves.push_back(Translation{p[j].tip, to, p[j].axis});
    if (j + 1 < p.size()) {
      const double th = axisAngle(p[j].axis, p[j + 1].axis);
      errorBound_ = std::max(errorBound_, 2.0 * reach * std::sin(th / 4.0));
    }
  }
  build(part, moves);
  if (bodies_.empty()) bounds_ = Aabb{p[0].tip, p[0].tip};
}

SweptVolume::SweptVolume(const ToolPart& part, const std::vector<Translation>& moves,
                         double errorBound)
    : errorBound_(errorBound) {
  build(part, moves);
  if (bodies_.empty()) bounds_ = Aabb{moves.front().from, moves.front().from};
}

void SweptVolume::build(const ToolPart& part, const std::vector<Translation>& moves) {
  // Runs with one axis along one line are one translation: exact, and cheaper.
  for (const Translation& m : moves) {
    if (!translations_.empty()) {
      Translation& run = translations_.back();
      if (run.axis == m.axis && run.to == m.from && collinearContinuation(run, m.to)) {
        run.to = m.to;
        continue;
      }
    }
    translations_.push_back(m);
  }
  bounds_ = emptyBox();
  // One lower envelope per body of the part, shared by all its translations.
  std::vector<int> profileOf;
  for (const ConvexBody& cb : part.bodies) {
    std::optional<AxialProfile> p = axialProfile(cb);
    profileOf.push_back(p ? static_cast<int>(profiles_.size()) : -1);
    if (p) profiles_.push_back(std::move(*p));
  }
  for (const Translation& tr : translations_) addTranslation(part, profileOf, tr);
  for (int a = 0; a < 3; ++a)
    rowKernel_[a] =
        !bodies_.empty() && std::all_of(bodies_.begin(), bodies_.end(), [&](const SweptBody& b) {
          return b.alongAxis == a && profiles_[b.profile].rises.size() <= kRowRises;
        });
  leans_ = std::any_of(bodies_.begin(), bodies_.end(), [](const SweptBody& b) {
    const glm::dvec3 a = glm::abs(b.axis);
    return !(a.x == 1.0 || a.y == 1.0 || a.z == 1.0);
  });
  for (int a = 0; a < 3; ++a)
    rowCross_[a] =
        !bodies_.empty() && std::all_of(bodies_.begin(), bodies_.end(),
                                        [&](const SweptBody& b) { return b.crossing[a]; });
}

void SweptVolume::addTranslation(const ToolPart& part, const std::vector<int>& profileOf,
                                 const Translation& tr) {
  const glm::dvec3 d = tr.to - tr.from;
  const double len = glm::length(d);
  const glm::dvec3 w = tr.axis;
  for (std::size_t bi = 0; bi < part.bodies.size(); ++bi) {
    const ConvexBody& cb = part.bodies[bi];
    SweptBody body;
    body.tip = tr.from;
    body.axis = w;
    body.length = len;
    body.dir = len > 0.0 ? d / len : glm::dvec3(0.0);
    const double zd = glm::dot(w, body.dir);
    for (int a = 0; a < 3; ++a) {
      AxisTerms& t = body.terms[a];
      t.ze = w[a];
      t.zd = zd;
      t.re2 = 1.0 - w[a] * w[a];
      t.rerd = body.dir[a] - w[a] * zd;
      t.rd2 = len > 0.0 ? 1.0 - zd * zd : 0.0;
      const int a1 = (a + 1) % 3;
      const int a2 = (a + 2) % 3;
      // The closed forms need the axis exactly on or square to the grid axis.
      if (std::abs(w[a]) == 1.0 && w[a1] == 0.0 && w[a2] == 0.0 && profileOf[bi] >= 0) {
        body.alongAxis = a;
        body.profile = profileOf[bi];
        body.along = AxialMove{body.dir[a1], body.dir[a2],
                               body.dir[a1] * body.dir[a1] + body.dir[a2] * body.dir[a2],
                               w[a] * body.dir[a], len};
      }
      if (w[a] == 0.0) {
        glm::dvec3 e(0.0);
        e[a] = 1.0;
        const glm::dvec3 n = glm::cross(w, e);
        body.crossing[a] = true;
        body.crossNormal[a] = n / glm::length(n);
        const double dn = glm::dot(body.dir, body.crossNormal[a]);
        body.cross[a] = CrossMove{zd, dn, body.dir[a], len, std::hypot(dn, body.dir[a])};
      }
    }
    // Candidates on an edge are kept within these; far below the grid's resolution.
    const double scale = part.reach() + len + 1.0;
    body.linearTol = 1e-12 * scale;
    body.quadricTol = 1e-13 * scale * scale;
    body.box = emptyBox();
    body.pieceBegin = static_cast<int>(pieces_.size());
    for (std::size_t pi = 0; pi < cb.pieces.size(); ++pi) {
      const RevolvedPiece& rp = cb.pieces[pi];
      SweptPiece sp{{rp.z0, rp.z1, rp.alpha, rp.beta, rp.gamma}, {}};
      sp.smoothBelow = pi > 0 && smoothJoin(cb.pieces[pi - 1], rp);
      sp.smoothAbove = pi + 1 < cb.pieces.size() && smoothJoin(rp, cb.pieces[pi + 1]);
      if (rp.sphere && sp.smoothAbove) {
        // The zone from the pole to the equator, the next piece a cylinder of the ball's
        // radius reaching over its top: the body is the whole ball and the rest.
        const RevolvedPiece& above = cb.pieces[pi + 1];
        const double r = rp.maxRadius(), eps = 1e-12 * (1.0 + r + std::abs(rp.centre));
        sp.capsule = std::abs(rp.z0 - (rp.centre - r)) <= eps &&
                     std::abs(rp.z1 - rp.centre) <= eps && !above.sphere && above.r0 == above.r1 &&
                     above.z1 >= rp.centre + r;
        sp.centre = rp.centre;
        sp.radius = r;
      }
      sp.maxRadius = rp.maxRadius();
      sp.box = cylinderBox(tr.from, w, rp.z0, rp.z1, rp.maxRadius());
      grow(sp.box, cylinderBox(tr.to, w, rp.z0, rp.z1, rp.maxRadius()));
      grow(body.box, sp.box);
      pieces_.push_back(sp);
    }
    body.pieceEnd = static_cast<int>(pieces_.size());
    grow(bounds_, body.box);
    bodies_.push_back(body);
  }
}

Aabb SweptVolume::boundsIn(const Aabb& box) const {
  if (!leans_) return LineSolid::boundsIn(box);
  Aabb r{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  const auto misses = [&](const Aabb& b) {
    for (int k = 0; k < 3; ++k)
      if (b.hi[k] < box.lo[k] || b.lo[k] > box.hi[k]) return true;
    return false;
  };
  for (const SweptBody& body : bodies_) {
    if (misses(body.box)) continue;
    for (int i = body.pieceBegin; i < body.pieceEnd; ++i) {
      const SweptPiece& p = pieces_[static_cast<std::size_t>(i)];
      if (misses(p.box)) continue;
      const Aabb b = sweptPieceBoundsIn(body.tip, body.length * body.dir, body.axis, p.q.z0, p.q.z1,
                                        p.maxRadius, box);
      if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z)) continue;
      r.lo = glm::min(r.lo, b.lo);
      r.hi = glm::max(r.hi, b.hi);
    }
  }
  return r;
}

// One line in the frame of one swept body: a line point at t (relative to the tip's
// coordinate), shifted back by s along the move, is at height z0 + ze t - zd s on the
// tool's axis and at radial offset r0 + t re - s rd from it.
struct SweptVolume::LineFrame {
  int axis, i1, i2;
  double u, v;
  double z0, r0re, r0rd, r0r0;
};

bool SweptVolume::pieceExtent(const SweptBody& body, const SweptPiece& p, const LineFrame& f,
                              bool general, double& lo, double& hi) const {
  const AxisTerms& k = body.terms[f.axis];
  if (p.capsule && !general) {
    // The line's origin from the ball's centre at the move's start, in dot products.
    const double c = p.centre;
    const double me = -c * k.ze, md = f.r0rd + f.z0 * k.zd - c * k.zd;
    const double mm = f.r0r0 + (f.z0 - c) * (f.z0 - c);
    return capsuleExtent(me, md, mm, body.dir[f.axis], body.length, p.radius, lo, hi);
  }
  const SectionTolerance tol{body.linearTol, body.quadricTol};
  // g = |r|^2 - alpha - beta z - gamma z^2, in (t, s)
  Quadric2 g;
  const PieceQuadric& q = p.q;
  g.a = k.re2 - q.gamma * k.ze * k.ze;
  g.b = -k.rerd + q.gamma * k.ze * k.zd;
  g.c = k.rd2 - q.gamma * k.zd * k.zd;
  g.d = f.r0re - 0.5 * q.beta * k.ze - q.gamma * f.z0 * k.ze;
  g.e = -f.r0rd + 0.5 * q.beta * k.zd + q.gamma * f.z0 * k.zd;
  g.f = f.r0r0 - q.alpha - q.beta * f.z0 - q.gamma * f.z0 * f.z0;
  if (k.ze != 0.0 && !general)
    return bandExtent(g,
                      Band{body.length, k.ze, k.zd, f.z0, q.z0, q.z1, p.smoothBelow, p.smoothAbove},
                      tol, lo, hi);
  if (k.ze != 0.0) {
    const HalfPlane h[4] = {{0.0, -1.0, 0.0},
                            {0.0, 1.0, -body.length},
                            {-k.ze, k.zd, q.z0 - f.z0},
                            {k.ze, -k.zd, f.z0 - q.z1}};
    return sectionExtent(g, h, tol, lo, hi);
  }
  // The line is square to the axis: z does not change along it, so the piece's z range
  // only limits s, and what is left is a strip (most lines of 3-axis work).
  double s0 = 0.0;
  double s1 = body.length;
  if (k.zd == 0.0) {
    if (f.z0 < q.z0 - tol.linear || f.z0 > q.z1 + tol.linear) return false;
  } else {
    const double a = (f.z0 - q.z1) / k.zd;
    const double b = (f.z0 - q.z0) / k.zd;
    s0 = std::max(s0, std::min(a, b));
    s1 = std::min(s1, std::max(a, b));
    if (s0 > s1) {
      if (s0 > s1 + tol.linear) return false;
      s0 = s1 = 0.5 * (s0 + s1);
    }
  }
  return stripExtent(g, s0, s1, tol, lo, hi);
}

bool SweptVolume::bodyInterval(const SweptBody& body, int axis, double u, double v, bool general,
                               Interval& out) const {
  LineFrame f{axis, (axis + 1) % 3, (axis + 2) % 3, u, v, 0, 0, 0, 0};
  glm::dvec3 delta(0.0);
  glm::value_ptr(delta)[f.i1] = u - coord(body.tip, f.i1);
  glm::value_ptr(delta)[f.i2] = v - coord(body.tip, f.i2);
  const AxisTerms& k = body.terms[axis];
  f.z0 = glm::dot(body.axis, delta);
  f.r0re = -f.z0 * k.ze;
  f.r0rd = glm::dot(delta, body.dir) - f.z0 * k.zd;
  f.r0r0 = glm::dot(delta, delta) - f.z0 * f.z0;
  const double base = coord(body.tip, axis);

  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  enum class Result { kMiss, kHit, kSkipped };
  auto solve = [&](int i) {
    const SweptPiece& p = pieces_[i];
    if (u < coord(p.box.lo, f.i1) || u > coord(p.box.hi, f.i1) || v < coord(p.box.lo, f.i2) ||
        v > coord(p.box.hi, f.i2))
      return Result::kMiss;
    if (coord(p.box.lo, axis) >= lo && coord(p.box.hi, axis) <= hi)
      return Result::kSkipped;  // inside hull
    double plo = 0.0;
    double phi = 0.0;
    if (!pieceExtent(body, p, f, general, plo, phi)) return Result::kMiss;
    lo = std::min(lo, plo + base);
    hi = std::max(hi, phi + base);
    return Result::kHit;
  };
  // The pieces a line meets are contiguous in the stack (the body's sweep is convex and
  // the pieces are slabs of it), so after the two ends a walk stops at its first miss
  // past a hit. Solving both ends first lets the hull skip the middle of a stack.
  const int top = body.pieceEnd - 1;
  const int bottom = body.pieceBegin;
  const bool topHit = solve(top) == Result::kHit;
  const bool bottomHit = bottom < top && solve(bottom) == Result::kHit;
  bool hit = topHit || bottomHit;
  const int step = topHit ? -1 : 1;
  for (int i = topHit ? top - 1 : bottom + 1; i > bottom && i < top; i += step) {
    const Result r = solve(i);
    if (r == Result::kMiss && hit) break;
    hit = hit || r == Result::kHit;
  }
  if (!(hi > lo)) return false;
  out = Interval{lo, hi};
  return true;
}

bool SweptVolume::crossBodyInterval(const SweptBody& body, int axis, double u, double v,
                                    Interval& out) const {
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  glm::dvec3 delta(0.0);
  glm::value_ptr(delta)[i1] = u - coord(body.tip, i1);
  glm::value_ptr(delta)[i2] = v - coord(body.tip, i2);
  const CrossMove& m = body.cross[axis];
  const double zeta0 = glm::dot(body.axis, delta);
  const double h0 = glm::dot(body.crossNormal[axis], delta);
  // The heights on the axis the line passes over s in [0, L].
  const double za = std::min(zeta0, zeta0 - m.length * m.zd) - body.linearTol;
  const double zb = std::max(zeta0, zeta0 - m.length * m.zd) + body.linearTol;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (int i = body.pieceBegin; i < body.pieceEnd; ++i) {
    const SweptPiece& p = pieces_[i];
    if (p.q.z1 < za || p.q.z0 > zb) continue;
    if (u < coord(p.box.lo, i1) || u > coord(p.box.hi, i1) || v < coord(p.box.lo, i2) ||
        v > coord(p.box.hi, i2))
      continue;
    double plo = 0.0;
    double phi = 0.0;
    if (!crossExtent(p.q, m, zeta0, h0, body.linearTol, body.quadricTol, plo, phi)) continue;
    lo = std::min(lo, plo);
    hi = std::max(hi, phi);
  }
  if (!(hi > lo)) return false;
  out = Interval{lo + coord(body.tip, axis), hi + coord(body.tip, axis)};
  return out.hi > out.lo;
}

void SweptVolume::lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const {
  intervals(axis, u, v, false, out);
}

bool SweptVolume::prismBand(int& axis, double& lo, double& hi) const {
  if (bodies_.empty()) return false;
  const int a = bodies_.front().alongAxis;
  if (a < 0) return false;
  double blo = -std::numeric_limits<double>::infinity(), bhi = -blo;
  for (const SweptBody& body : bodies_) {
    if (body.alongAxis != a) return false;
    const AxialProfile& p = profiles_[body.profile];
    const double w = body.axis[a];  // +-1
    const double t0 = body.tip[a], t1 = t0 + body.length * body.dir[a];
    // Heights h = (c - tip) * w in [riseTop, top] at both ends of the move.
    const double lo1 = w > 0 ? std::max(t0, t1) + p.riseTop : std::max(t0, t1) - p.top;
    const double hi1 = w > 0 ? std::min(t0, t1) + p.top : std::min(t0, t1) - p.riseTop;
    // A body that does not reach the band leaves its sections alone.
    if (body.box.hi[a] < blo || body.box.lo[a] > bhi) continue;
    blo = std::max(blo, lo1);
    bhi = std::min(bhi, hi1);
  }
  if (!(bhi > blo)) return false;
  axis = a;
  lo = blo;
  hi = bhi;
  return true;
}

void SweptVolume::generalLineIntervals(int axis, double u, double v,
                                       std::vector<Interval>& out) const {
  intervals(axis, u, v, true, out);
}

void SweptVolume::intervals(int axis, double u, double v, bool general,
                            std::vector<Interval>& out) const {
  if (axis < 0 || axis > 2) return;
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  if (u < coord(bounds_.lo, i1) || u > coord(bounds_.hi, i1) || v < coord(bounds_.lo, i2) ||
      v > coord(bounds_.hi, i2))
    return;
  const size_t first = out.size();
  for (const SweptBody& body : bodies_) {
    if (u < coord(body.box.lo, i1) || u > coord(body.box.hi, i1) || v < coord(body.box.lo, i2) ||
        v > coord(body.box.hi, i2))
      continue;
    // A body whose box along the line lies inside an interval found already cannot
    // add to the union (consecutive steps of a 5-axis move overlap this way).
    bool covered = false;
    for (size_t i = first; i < out.size() && !covered; ++i)
      covered = coord(body.box.lo, axis) >= out[i].lo && coord(body.box.hi, axis) <= out[i].hi;
    if (covered) continue;
    Interval iv;
    bool hit = false;
    if (general) {
      hit = bodyInterval(body, axis, u, v, true, iv);
    } else if (body.alongAxis == axis) {
      double lo = 0.0;
      double hi = 0.0;
      hit = axialExtent(profiles_[body.profile], body.along, u - coord(body.tip, i1),
                        v - coord(body.tip, i2), body.linearTol, lo, hi);
      iv = axialInterval(body, axis, lo, hi);
    } else if (body.crossing[axis]) {
      hit = crossBodyInterval(body, axis, u, v, iv);
    } else {
      hit = bodyInterval(body, axis, u, v, false, iv);
    }
    if (hit && iv.hi > iv.lo) out.push_back(iv);
  }
  mergeFrom(out, first);
}

Interval SweptVolume::axialInterval(const SweptBody& body, int axis, double lo, double hi) {
  // Heights run along the line with the axis' sign.
  const double base = coord(body.tip, axis);
  return coord(body.axis, axis) > 0.0 ? Interval{base + lo, base + hi}
                                      : Interval{base - hi, base - lo};
}

}  // namespace mdhd::geom

// SweptVolume's answers for many lines at once: body by body, each body's lines
// through a branch-free kernel (axialExtentRow for lines along a 3-axis tool,
// crossExtentRow for lines square to it), the same answers to the bit as asking
// line by line (lineIntervals), for less per line.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "sim/geometry/swept_volume.h"

namespace mdhd::geom {

namespace {

inline double coord(const glm::dvec3& v, int i) {
  return glm::value_ptr(v)[i];
}

// Each line's union so far, body by body: while every interval meets the union of
// those before it, the union is one interval, their hull (what sorting and merging
// gives, to the bit). A line where one does not (rare: a chain crossing a line
// twice) is marked to be asked again on its own.
struct LineHulls {
  std::vector<Interval> hull;
  std::vector<unsigned char> any, apart;

  void reset(std::size_t n) {
    any.assign(n, 0);
    apart.assign(n, 0);
    hull.resize(n);
  }
  void add(std::size_t i, const Interval& iv) {
    Interval& h = hull[i];
    if (!any[i]) {
      h = iv;
      any[i] = 1;
      return;
    }
    apart[i] |= !(iv.lo <= h.hi && h.lo <= iv.hi);
    h = Interval{std::min(h.lo, iv.lo), std::max(h.hi, iv.hi)};
  }
  // Appends line i's intervals for every line; `again(i)` asks a line apart on its own.
  template <class Again>
  void emit(std::vector<Interval>& out, std::span<std::size_t> ends, Again again) const {
    for (std::size_t i = 0; i < ends.size(); ++i) {
      if (apart[i])
        again(i);
      else if (any[i])
        out.push_back(hull[i]);
      ends[i] = out.size();
    }
  }
};

}  // namespace

void SweptVolume::rowIntervals(int axis, std::span<const double> us, double v,
                               std::vector<Interval>& out, std::span<std::size_t> ends) const {
  const std::size_t n = us.size();
  const bool meets =
      axis >= 0 && axis <= 2 && n > 0 &&
      !(v < coord(bounds_.lo, (axis + 2) % 3) || v > coord(bounds_.hi, (axis + 2) % 3));
  if (!meets) {
    std::fill(ends.begin(), ends.end(), out.size());
    return;
  }
  if (!rowKernel_[axis]) {
    if (rowCross_[axis]) {
      // Lines square to every body: the general form, all at this v.
      thread_local std::vector<double> vs;
      vs.assign(n, v);
      crossLinesIntervals(axis, us, vs, out, ends);
      return;
    }
    // Bodies off the lines' axis gain nothing body by body (and lose the skip of a
    // body inside what the line holds already, which turning moves live on).
    LineSolid::rowIntervals(axis, us, v, out, ends);
    return;
  }
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  struct Scratch {
    LineHulls hulls;
    std::vector<double> q1, lo, hi;
    std::vector<unsigned char> hit;
  };
  thread_local Scratch s;
  s.hulls.reset(n);
  for (const SweptBody& body : bodies_) {
    if (v < coord(body.box.lo, i2) || v > coord(body.box.hi, i2)) continue;
    // The lines whose u the body's box holds (a line outside it misses the body).
    const std::size_t b = static_cast<std::size_t>(
        std::lower_bound(us.begin(), us.end(), coord(body.box.lo, i1)) - us.begin());
    const std::size_t e = static_cast<std::size_t>(
        std::upper_bound(us.begin() + b, us.end(), coord(body.box.hi, i1)) - us.begin());
    if (b >= e) continue;
    const std::size_t m = e - b;
    s.q1.resize(m), s.lo.resize(m), s.hi.resize(m), s.hit.resize(m);
    const double tip1 = coord(body.tip, i1);
    for (std::size_t j = 0; j < m; ++j) s.q1[j] = us[b + j] - tip1;
    axialExtentRow(profiles_[body.profile], body.along, s.q1.data(), v - coord(body.tip, i2), m,
                   body.linearTol, s.lo.data(), s.hi.data(), s.hit.data());
    for (std::size_t j = 0; j < m; ++j) {
      const Interval iv = axialInterval(body, axis, s.lo[j], s.hi[j]);
      if (s.hit[j] && iv.hi > iv.lo) s.hulls.add(b + j, iv);
    }
  }
  s.hulls.emit(out, ends, [&](std::size_t i) { lineIntervals(axis, us[i], v, out); });
}

void SweptVolume::linesIntervals(int axis, std::span<const double> us, std::span<const double> vs,
                                 std::vector<Interval>& out, std::span<std::size_t> ends) const {
  if (axis >= 0 && axis <= 2 && rowCross_[axis]) {
    crossLinesIntervals(axis, us, vs, out, ends);
    return;
  }
  LineSolid::linesIntervals(axis, us, vs, out, ends);
}

void SweptVolume::crossLinesIntervals(int axis, std::span<const double> us,
                                      std::span<const double> vs, std::vector<Interval>& out,
                                      std::span<std::size_t> ends) const {
  // crossBodyInterval body by body: its per-line values computed as it does, then
  // each piece over the lines its tests keep, through crossExtentRow.
  const std::size_t n = us.size();
  const int i1 = (axis + 1) % 3;
  const int i2 = (axis + 2) % 3;
  struct Scratch {
    LineHulls hulls;
    std::vector<std::uint32_t> inBody, inPiece;
    std::vector<double> zeta, h0, za, zb, lo, hi;  // per line of the body
    std::vector<double> pz, ph, plo, phi;          // per line of the piece
    std::vector<unsigned char> hit;
  };
  thread_local Scratch s;
  s.hulls.reset(n);
  for (const SweptBody& body : bodies_) {
    const double u0 = coord(body.box.lo, i1), u1 = coord(body.box.hi, i1);
    const double v0 = coord(body.box.lo, i2), v1 = coord(body.box.hi, i2);
    // The lines the body's box holds, but those whose union so far holds the body's
    // box along them already (lineIntervals skips them too: consecutive steps of a
    // pass, seen from across it, are such bodies).
    const double a0 = coord(body.box.lo, axis), a1 = coord(body.box.hi, axis);
    s.inBody.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const Interval& h = s.hulls.hull[i];
      const bool covered = s.hulls.any[i] & !s.hulls.apart[i] & (a0 >= h.lo) & (a1 <= h.hi);
      if (!(us[i] < u0 || us[i] > u1 || vs[i] < v0 || vs[i] > v1 || covered))
        s.inBody.push_back(static_cast<std::uint32_t>(i));
    }
    const std::size_t m = s.inBody.size();
    if (m == 0) continue;
    s.zeta.resize(m), s.h0.resize(m), s.za.resize(m), s.zb.resize(m);
    s.lo.assign(m, std::numeric_limits<double>::infinity());
    s.hi.assign(m, -std::numeric_limits<double>::infinity());
    const CrossMove& mv = body.cross[axis];
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t i = s.inBody[j];
      glm::dvec3 delta(0.0);
      glm::value_ptr(delta)[i1] = us[i] - coord(body.tip, i1);
      glm::value_ptr(delta)[i2] = vs[i] - coord(body.tip, i2);
      const double zeta0 = glm::dot(body.axis, delta);
      s.zeta[j] = zeta0;
      s.h0[j] = glm::dot(body.crossNormal[axis], delta);
      // The heights on the axis the line passes over s in [0, L].
      s.za[j] = std::min(zeta0, zeta0 - mv.length * mv.zd) - body.linearTol;
      s.zb[j] = std::max(zeta0, zeta0 - mv.length * mv.zd) + body.linearTol;
    }
    for (int pi = body.pieceBegin; pi < body.pieceEnd; ++pi) {
      const SweptPiece& p = pieces_[pi];
      const double pu0 = coord(p.box.lo, i1), pu1 = coord(p.box.hi, i1);
      const double pv0 = coord(p.box.lo, i2), pv1 = coord(p.box.hi, i2);
      s.inPiece.clear();
      for (std::size_t j = 0; j < m; ++j) {
        const std::size_t i = s.inBody[j];
        if (p.q.z1 < s.za[j] || p.q.z0 > s.zb[j]) continue;
        if (us[i] < pu0 || us[i] > pu1 || vs[i] < pv0 || vs[i] > pv1) continue;
        s.inPiece.push_back(static_cast<std::uint32_t>(j));
      }
      const std::size_t k = s.inPiece.size();
      if (k == 0) continue;
      s.pz.resize(k), s.ph.resize(k), s.plo.resize(k), s.phi.resize(k), s.hit.resize(k);
      for (std::size_t t = 0; t < k; ++t) {
        s.pz[t] = s.zeta[s.inPiece[t]];
        s.ph[t] = s.h0[s.inPiece[t]];
      }
      crossExtentRow(p.q, mv, s.pz.data(), s.ph.data(), k, body.linearTol, body.quadricTol,
                     s.plo.data(), s.phi.data(), s.hit.data());
      for (std::size_t t = 0; t < k; ++t) {
        if (!s.hit[t]) continue;
        const std::size_t j = s.inPiece[t];
        s.lo[j] = std::min(s.lo[j], s.plo[t]);
        s.hi[j] = std::max(s.hi[j], s.phi[t]);
      }
    }
    const double tip = coord(body.tip, axis);
    for (std::size_t j = 0; j < m; ++j) {
      if (!(s.hi[j] > s.lo[j])) continue;
      const Interval iv{s.lo[j] + tip, s.hi[j] + tip};
      if (iv.hi > iv.lo) s.hulls.add(s.inBody[j], iv);
    }
  }
  s.hulls.emit(out, ends, [&](std::size_t i) { lineIntervals(axis, us[i], vs[i], out); });
}

}  // namespace mdhd::geom

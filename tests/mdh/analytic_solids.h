#pragma once
// Small exact LineSolids for the mdh tests: box, sphere, capsule (ball end
// mill), cylinder of any axis (flat end mill, shank), and unions of them.
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "sim/geometry/line_solid.h"

namespace mdhd::mdh::testing {

using geom::Aabb;
using geom::Interval;

inline glm::dvec3 linePoint(int axis, double u, double v) {
  glm::dvec3 p(0.0);
  p[(axis + 1) % 3] = u;
  p[(axis + 2) % 3] = v;
  return p;
}

inline glm::dvec3 unitAxis(int axis) {
  glm::dvec3 d(0.0);
  d[axis] = 1.0;
  return d;
}

// t-range where |o + t d - c|^2 <= r^2.
inline bool sphereRange(glm::dvec3 o, glm::dvec3 d, glm::dvec3 c, double r, Interval& out) {
  const glm::dvec3 m = o - c;
  const double b = glm::dot(m, d), cc = glm::dot(m, m) - r * r;
  const double disc = b * b - cc;
  if (disc < 0) return false;
  const double s = std::sqrt(disc);
  out = {-b - s, -b + s};
  return out.hi > out.lo;
}

// Points of the line within distance r of the axis line through c along w
// and with axial coordinate in [s0, s1] (s measured from c along w).
inline bool cylinderRange(glm::dvec3 o, glm::dvec3 d, glm::dvec3 c, glm::dvec3 w, double r,
                          double s0, double s1, Interval& out) {
  const glm::dvec3 m = o - c;
  const glm::dvec3 dp = d - glm::dot(d, w) * w, mp = m - glm::dot(m, w) * w;
  double lo = -1e300, hi = 1e300;
  const double a = glm::dot(dp, dp), b = glm::dot(mp, dp), cc = glm::dot(mp, mp) - r * r;
  if (a < 1e-14) {
    if (cc > 0) return false;
  } else {
    const double disc = b * b - a * cc;
    if (disc <= 0) return false;
    const double s = std::sqrt(disc);
    lo = (-b - s) / a;
    hi = (-b + s) / a;
  }
  const double dw = glm::dot(d, w), mw = glm::dot(m, w);
  if (std::abs(dw) < 1e-14) {
    if (mw < s0 || mw > s1) return false;
  } else {
    double t0 = (s0 - mw) / dw, t1 = (s1 - mw) / dw;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
  }
  if (!(hi > lo)) return false;
  out = {lo, hi};
  return true;
}

class BoxSolid : public geom::LineSolid {
 public:
  BoxSolid(glm::dvec3 lo, glm::dvec3 hi) : lo_(lo), hi_(hi) {}
  Aabb bounds() const override { return {lo_, hi_}; }
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    if (u < lo_[a] || u > hi_[a] || v < lo_[b] || v > hi_[b]) return;
    out.push_back({lo_[axis], hi_[axis]});
  }

 private:
  glm::dvec3 lo_, hi_;
};

class SphereSolid : public geom::LineSolid {
 public:
  SphereSolid(glm::dvec3 c, double r) : c_(c), r_(r) {}
  Aabb bounds() const override { return {c_ - r_, c_ + r_}; }
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override {
    Interval i;
    if (sphereRange(linePoint(axis, u, v), unitAxis(axis), c_, r_, i)) out.push_back(i);
  }

 private:
  glm::dvec3 c_;
  double r_;
};

// All points within r of segment [p0, p1]: a ball end mill from tip centre p0.
class CapsuleSolid : public geom::LineSolid {
 public:
  CapsuleSolid(glm::dvec3 p0, glm::dvec3 p1, double r) : p0_(p0), p1_(p1), r_(r) {}
  Aabb bounds() const override { return {glm::min(p0_, p1_) - r_, glm::max(p0_, p1_) + r_}; }
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override {
    const glm::dvec3 o = linePoint(axis, u, v), d = unitAxis(axis);
    const double len = glm::length(p1_ - p0_);
    double lo = 1e300, hi = -1e300;
    Interval i;
    for (const glm::dvec3& c : {p0_, p1_})
      if (sphereRange(o, d, c, r_, i)) lo = std::min(lo, i.lo), hi = std::max(hi, i.hi);
    if (len > 0 && cylinderRange(o, d, p0_, (p1_ - p0_) / len, r_, 0.0, len, i))
      lo = std::min(lo, i.lo), hi = std::max(hi, i.hi);
    if (hi > lo) out.push_back({lo, hi});  // a capsule is convex: one interval
  }

 private:
  glm::dvec3 p0_, p1_;
  double r_;
};

// Flat-ended cylinder from `base` along unit `axis` for `height`.
class CylinderSolid : public geom::LineSolid {
 public:
  CylinderSolid(glm::dvec3 base, glm::dvec3 axis, double r, double height)
      : base_(base), w_(glm::normalize(axis)), r_(r), height_(height) {}
  Aabb bounds() const override {
    const glm::dvec3 top = base_ + w_ * height_;
    return {glm::min(base_, top) - r_, glm::max(base_, top) + r_};
  }
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override {
    Interval i;
    if (cylinderRange(linePoint(axis, u, v), unitAxis(axis), base_, w_, r_, 0.0, height_, i))
      out.push_back(i);
  }

 private:
  glm::dvec3 base_, w_;
  double r_, height_;
};

class UnionSolid : public geom::LineSolid {
 public:
  explicit UnionSolid(std::vector<std::shared_ptr<geom::LineSolid>> parts)
      : parts_(std::move(parts)) {}
  Aabb bounds() const override {
    Aabb b{glm::dvec3(1e300), glm::dvec3(-1e300)};
    for (const auto& p : parts_) {
      const Aabb pb = p->bounds();
      b.lo = glm::min(b.lo, pb.lo);
      b.hi = glm::max(b.hi, pb.hi);
    }
    return b;
  }
  void lineIntervals(int axis, double u, double v, std::vector<Interval>& out) const override {
    std::vector<Interval> all;
    for (const auto& p : parts_) p->lineIntervals(axis, u, v, all);
    std::sort(all.begin(), all.end(), [](auto& a, auto& b) { return a.lo < b.lo; });
    for (const Interval& i : all) {
      if (!out.empty() && i.lo <= out.back().hi)
        out.back().hi = std::max(out.back().hi, i.hi);
      else
        out.push_back(i);
    }
  }

 private:
  std::vector<std::shared_ptr<geom::LineSolid>> parts_;
};

// A ball end mill (radius r, tip centre `tip`, axis `dir` towards the
// spindle) with its shank, as one solid.
inline std::shared_ptr<geom::LineSolid> ballMill(glm::dvec3 tip, glm::dvec3 dir, double r,
                                                 double length) {
  dir = glm::normalize(dir);
  return std::make_shared<CapsuleSolid>(tip, tip + dir * length, r);
}

inline std::shared_ptr<geom::LineSolid> flatMill(glm::dvec3 tip, glm::dvec3 dir, double r,
                                                 double length) {
  return std::make_shared<CylinderSolid>(tip, glm::normalize(dir), r, length);
}

}  // namespace mdhd::mdh::testing

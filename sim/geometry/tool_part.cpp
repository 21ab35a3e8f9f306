#include "sim/geometry/tool_part.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace mdhd::geom {

double RevolvedPiece::radiusAt(double z) const {
  const double r2 = alpha + beta * z + gamma * z * z;
  return r2 > 0.0 ? std::sqrt(r2) : 0.0;
}

double RevolvedPiece::maxRadius() const {
  if (sphere && centre >= z0 && centre <= z1) return radiusAt(centre);
  return std::max(r0, r1);
}

RevolvedPiece cylinderPiece(double z0, double z1, double radius) {
  return frustumPiece(z0, z1, radius, radius);
}

RevolvedPiece frustumPiece(double z0, double z1, double r0, double r1) {
  // rho <= m + k z, squared; m + k z >= 0 on [z0, z1] keeps the square convex.
  const double k = (r1 - r0) / (z1 - z0);
  const double m = r0 - k * z0;
  RevolvedPiece p;
  p.z0 = z0;
  p.z1 = z1;
  p.alpha = m * m;
  p.beta = 2.0 * m * k;
  p.gamma = k * k;
  p.r0 = r0;
  p.r1 = r1;
  return p;
}

RevolvedPiece spherePiece(double centre, double radius, double z0, double z1) {
  // rho^2 <= radius^2 - (z - centre)^2
  RevolvedPiece p;
  p.z0 = z0;
  p.z1 = z1;
  p.alpha = radius * radius - centre * centre;
  p.beta = 2.0 * centre;
  p.gamma = -1.0;
  p.sphere = true;
  p.centre = centre;
  p.r0 = p.radiusAt(z0);
  p.r1 = p.radiusAt(z1);
  return p;
}

bool smoothJoin(const RevolvedPiece& below, const RevolvedPiece& above) {
  const double z = below.z1;
  const double scale = 1.0 + std::abs(z) + below.maxRadius() + above.maxRadius();
  // Radius squared and its derivative alpha + beta z + gamma z^2, beta + 2 gamma z.
  const double r2b = below.alpha + (below.beta + below.gamma * z) * z;
  const double r2a = above.alpha + (above.beta + above.gamma * z) * z;
  const double db = below.beta + 2.0 * below.gamma * z;
  const double da = above.beta + 2.0 * above.gamma * z;
  return std::abs(above.z0 - z) <= 1e-12 * scale && std::abs(r2b - r2a) <= 1e-12 * scale * scale &&
         std::abs(db - da) <= 1e-12 * scale && r2b > 1e-12 * scale * scale;
}

double ConvexBody::radiusAt(double z) const {
  for (const RevolvedPiece& p : pieces)
    if (z >= p.z0 && z <= p.z1) return p.radiusAt(z);
  return 0.0;
}

double ToolPart::reach(double height) const {
  double r = 0.0;
  for (const ConvexBody& b : bodies)
    for (const RevolvedPiece& p : b.pieces) {
      const double z = std::max(std::abs(p.z0 - height), std::abs(p.z1 - height));
      r = std::max(r, std::hypot(p.maxRadius(), z));
    }
  return r;
}

double ToolPart::maxRadius() const {
  double r = 0.0;
  for (const ConvexBody& b : bodies)
    for (const RevolvedPiece& p : b.pieces) r = std::max(r, p.maxRadius());
  return r;
}

double ToolPart::centreHeight() const {
  if (bodies.empty()) return 0.0;
  double lo = bodies.front().bottom();
  double hi = bodies.front().top();
  for (const ConvexBody& b : bodies) {
    lo = std::min(lo, b.bottom());
    hi = std::max(hi, b.top());
  }
  return 0.5 * (lo + hi);
}

double ToolPart::turnRate(double height) const {
  double rate = 0.0;
  auto crease = [&](double r, double z) { rate = std::max(rate, std::hypot(r, z - height)); };
  for (const ConvexBody& b : bodies) {
    for (std::size_t i = 0; i < b.pieces.size(); ++i) {
      const RevolvedPiece& p = b.pieces[i];
      if (p.sphere) {
        rate = std::max(rate, std::abs(p.centre - height));
      } else if (p.z1 > p.z0) {
        // |z + r r'| / sqrt(1 + r'^2) is linear over sqrt(const) on a frustum: its ends.
        const double slope = (p.r1 - p.r0) / (p.z1 - p.z0);
        const double g0 = p.z0 - height + p.r0 * slope, g1 = p.z1 - height + p.r1 * slope;
        rate = std::max(rate, std::max(std::abs(g0), std::abs(g1)) / std::hypot(1.0, slope));
      }
      // The rim below the piece (a face's edge, a cone's apex, a crease between pieces);
      // a ball zone's pole and smooth joins are none.
      if (i == 0 ? !(p.sphere && p.r0 == 0.0) : !smoothJoin(b.pieces[i - 1], p)) crease(p.r0, p.z0);
    }
    const RevolvedPiece& top = b.pieces.back();
    if (!(top.sphere && top.r1 == 0.0)) crease(top.r1, top.z1);
  }
  return rate;
}

double ToolPart::turnPivot() const {
  if (bodies.empty()) return 0.0;
  // turnRate is a maximum of convex functions of the height (absolute values of linear
  // ones, hypotenuses): a golden-section search over the part's height finds its least.
  double lo = bodies.front().bottom(), hi = bodies.front().top();
  for (const ConvexBody& b : bodies) {
    lo = std::min(lo, b.bottom());
    hi = std::max(hi, b.top());
  }
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  double f1 = turnRate(x1), f2 = turnRate(x2);
  for (int i = 0; i < 80 && hi - lo > 1e-9 * (1.0 + std::abs(hi)); ++i) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - phi * (hi - lo), f1 = turnRate(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + phi * (hi - lo), f2 = turnRate(x2);
    }
  }
  return 0.5 * (lo + hi);
}

namespace {

// Frustums through points of the corner arc (centre (a, rc) in the rho-z plane), as
// few as keep the chord's sag within the tolerance.
void addTorusCorner(ConvexBody& body, double a, double rc, double tolerance) {
  const double quarter = std::numbers::pi / 2.0;
  const double maxAngle = tolerance >= rc ? quarter : 2.0 * std::acos(1.0 - tolerance / rc);
  const int n = std::max(1, static_cast<int>(std::ceil(quarter / maxAngle)));
  auto point = [&](int k, double& rho, double& z) {
    const double th = -quarter + quarter * k / n;
    rho = a + rc * std::cos(th);
    z = rc + rc * std::sin(th);
  };
  double rho0 = a;
  double z0 = 0.0;
  for (int k = 1; k <= n; ++k) {
    double rho1 = 0.0;
    double z1 = 0.0;
    point(k, rho1, z1);
    if (k == n) {  // the exact top, so the cylinder above meets it
      z1 = rc;
      rho1 = a + rc;
    }
    body.pieces.push_back(frustumPiece(z0, z1, rho0, rho1));
    rho0 = rho1;
    z0 = z1;
  }
}

ConvexBody cutterBody(const Tool& t, double cornerTolerance) {
  ConvexBody body;
  const double r = t.radius();
  double top = 0.0;  // where the straight flutes begin
  switch (t.shape) {
    case ToolShape::kFlat:
      break;
    case ToolShape::kBall:
      body.pieces.push_back(spherePiece(r, r, 0.0, r));
      top = r;
      break;
    case ToolShape::kBull:
      addTorusCorner(body, r - t.corner_radius, t.corner_radius, cornerTolerance);
      top = t.corner_radius;
      break;
    case ToolShape::kDrill:
      top = t.tipHeight();
      body.pieces.push_back(frustumPiece(0.0, top, 0.0, r));
      break;
  }
  if (t.flute_length > top) body.pieces.push_back(cylinderPiece(top, t.flute_length, r));
  return body;
}

}  // namespace

ToolPart makeToolPart(const Tool& tool, ToolPartKind kind, double corner_tolerance) {
  if (auto problem = validateTool(tool))
    throw std::invalid_argument("tool " + std::to_string(tool.number) + ": " + problem->field +
                                ": " + problem->message);
  if (!(corner_tolerance > 0.0))
    throw std::invalid_argument("tool part: corner tolerance must be > 0");
  ToolPart part;
  part.kind = kind;
  switch (kind) {
    case ToolPartKind::kCutter:
      part.bodies.push_back(cutterBody(tool, corner_tolerance));
      break;
    case ToolPartKind::kShank:
      if (tool.holderBottom() > tool.flute_length)
        part.bodies.push_back(ConvexBody{
            {cylinderPiece(tool.flute_length, tool.holderBottom(), tool.shank_diameter / 2.0)}});
      break;
    case ToolPartKind::kHolder: {
      // Listed from the gauge point down; each cylinder is its own convex body.
      double top = tool.length;
      for (const HolderSection& h : tool.holder) {
        part.bodies.push_back(ConvexBody{{cylinderPiece(top - h.length, top, h.diameter / 2.0)}});
        top -= h.length;
      }
      break;
    }
  }
  return part;
}

}  // namespace mdhd::geom

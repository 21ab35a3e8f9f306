#include "bench/check/dome_programs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mdhd::bench {
namespace {

double tipZ(double x, double y, double cx, double cy) {
  const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
  const double s = (kSphere + kBall) * (kSphere + kBall) - d2;
  const double dome = s > 0 ? kCentreZ + std::sqrt(s) - kBall : -1e9;
  return std::max(kFloor, dome);
}

std::string fmt(const char* f, double a, double b, double c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

// Where pass j of the zigzag starts.
void passStart(int lines, int j, double x0, double x1, double y0, double y1, double& x, double& y) {
  x = j % 2 == 0 ? x0 : x1;
  y = y0 + j * (y1 - y0) / (lines - 1);
}

// The zigzag's points in order: (x, y) of every G1 after the first plunge (at the
// start of pass `first`). passes >= 0: only that many passes from `first` on (a slice
// of the same program, for profiling).
template <typename Emit>
void zigzag(int lines, int pts, int first, int passes, double x0, double x1, double y0, double y1,
            Emit emit) {
  const double dy = (y1 - y0) / (lines - 1), dx = (x1 - x0) / pts;
  const int end = passes >= 0 ? std::min(lines, first + passes) : lines;
  for (int j = first; j < end; ++j) {
    const double y = y0 + j * dy;
    if (j > first) emit(j % 2 == 0 ? x0 : x1, y);
    for (int i = 1; i <= pts; ++i) emit(j % 2 == 0 ? x0 + i * dx : x1 - i * dx, y);
  }
}

}  // namespace

double domeZ(double x, double y, double cx, double cy) {
  const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
  const double s = kSphere * kSphere - d2;
  return std::max(kFloor, s > 0 ? kCentreZ + std::sqrt(s) : -1e9);
}

DomeProgram domeProgram(int lines, int pts, bool setup, int passes, int first) {
  DomeProgram p;
  p.text = "(dome zigzag finishing)\nG21\nG90\nG17\n";
  if (setup) p.text += "T1 M6\nG43 H1\nM3 S10000\n";
  p.text += fmt("G0 Z%.4f\n", kSafe, 0, 0);
  double xs = 0.0, ys = 0.0;
  passStart(lines, first, 0, 100, 0, 100, xs, ys);
  p.text += fmt("G0 X%.4f Y%.4f\n", xs, ys, 0);
  p.text += fmt("G1 Z%.4f F1000\n", tipZ(xs, ys, 50, 50), 0, 0);
  p.moves = 3;
  zigzag(lines, pts, first, passes, 0, 100, 0, 100, [&](double x, double y) {
    p.text += fmt("G1 X%.4f Y%.4f Z%.4f\n", x, y, tipZ(x, y, 50, 50));
    ++p.moves;
  });
  p.text += fmt("G0 Z%.4f\n", kSafe, 0, 0);
  ++p.moves;
  p.text += "M2\n";
  return p;
}

DomeProgram tiltedDomeProgram(const kin::Kinematics& kin, double tool_length, int lines, int pts,
                              int passes, int first) {
  constexpr double kTilt = -15.0;
  auto cAt = [](double x) { return -30.0 + 60.0 * (x + 50.0) / 100.0; };
  auto tip = [&](double x, double y, double c) {
    kin::JointValues q{};
    q[gcode::kA] = kTilt;
    q[gcode::kC] = c;
    const glm::dvec3 axis = kin.toolPose(q, tool_length).axis;
    const double d2 = x * x + y * y;
    const double s = (kSphere + kBall) * (kSphere + kBall) - d2;
    const double cz = std::max(kFloor + kBall, s > 0 ? kCentreZ + std::sqrt(s) : -1e9);
    return glm::dvec3(x, y, cz) - kBall * axis;
  };
  DomeProgram p;
  p.text = "(tilted ball dome, AC trunnion, G43.4)\nG21 G90 G17\nT1 M6\nM3 S10000\n";
  double xs = 0.0, ys = 0.0;
  passStart(lines, first, -50, 50, -50, 50, xs, ys);
  p.text += fmt("G0 A%.4f C%.4f\n", kTilt, cAt(xs), 0);
  p.text += "G43.4 H1\n";
  const glm::dvec3 t0 = tip(xs, ys, cAt(xs));
  p.text += fmt("G0 X%.4f Y%.4f Z%.4f\n", t0.x, t0.y, kSafe);
  p.text += fmt("G1 Z%.4f F1000\n", t0.z, 0, 0);
  p.moves = 3;
  glm::dvec3 last = t0;
  double lastC = cAt(xs);
  zigzag(lines, pts, first, passes, -50, 50, -50, 50, [&](double x, double y) {
    lastC = cAt(x);
    last = tip(x, y, lastC);
    p.text += fmt("G1 X%.4f Y%.4f Z%.4f", last.x, last.y, last.z) + fmt(" C%.4f\n", lastC, 0, 0);
    ++p.moves;
  });
  // Out along the tilted tool axis: straight up in W would drag the flutes sideways
  // through the material beside the tool.
  kin::JointValues q{};
  q[gcode::kA] = kTilt;
  q[gcode::kC] = lastC;
  const glm::dvec3 out = last + 40.0 * kin.toolPose(q, tool_length).axis;
  p.text += fmt("G0 X%.4f Y%.4f Z%.4f\n", out.x, out.y, out.z);
  ++p.moves;
  p.text += "G49\nM2\n";
  return p;
}

}  // namespace mdhd::bench

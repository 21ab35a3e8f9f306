// Figures for the swept volumes: nanoseconds per lineIntervals call over every grid line
// (0.1 mm) of the lowest 6 mm of one step's box, per tool shape and line direction, for
// a 3-axis move (closed forms), the same move with the axis held tilted 15 degrees and
// a 5-axis step turning 2 degrees (tolerance 0.01 mm; both through the section solver),
// each against generalLineIntervals (the section solver for every line: the path
// before the closed forms) on the same lines in the same run; a plain ray-sphere
// intersection over a 6 mm sphere's lines for scale. "steps/s": swept volumes built
// per second. Last, a 3-axis batch as the stock cuts it (16 short moves of each tool
// along a curved zigzag pass): its z lines row by row (rowIntervals, the vectorised
// body-by-body kernel) against line by line (lineIntervals), per line and per (line,
// body) pair whose box holds the line; and its x and y lines in the lowest 6 mm, in
// batches of about a brick's (linesIntervals, body by body and piece by piece through
// crossExtentRow) against line by line.
//
//   bench_swept_volume [--seconds S]   (S per case and direction, default 0.5)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_part.h"

namespace {

using namespace mdhd::geom;
using Clock = std::chrono::steady_clock;

constexpr double kGrid = 0.1;

struct Line {
  int axis;
  double u, v;
};

std::vector<Line> gridLines(const Aabb& b) {
  std::vector<Line> lines;
  for (int axis = 0; axis < 3; ++axis) {
    const int i1 = (axis + 1) % 3;
    const int i2 = (axis + 2) % 3;
    for (double u = std::floor(b.lo[i1] / kGrid) * kGrid; u <= b.hi[i1]; u += kGrid)
      for (double v = std::floor(b.lo[i2] / kGrid) * kGrid; v <= b.hi[i2]; v += kGrid)
        lines.push_back({axis, u, v});
  }
  return lines;
}

struct Rate {
  double callsPerSecond = 0;
  double hitFraction = 0;
};

// Calls `call` on every line, over and over, for `seconds`.
Rate measure(const std::vector<Line>& lines, double seconds,
             const std::function<void(const Line&, std::vector<Interval>&)>& call) {
  std::vector<Interval> out;
  out.reserve(16);
  long calls = 0;
  long hits = 0;
  const auto start = Clock::now();
  double elapsed = 0;
  do {
    for (const Line& l : lines) {
      out.clear();
      call(l, out);
      hits += !out.empty();
    }
    calls += static_cast<long>(lines.size());
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < seconds);
  return {calls / elapsed, double(hits) / calls};
}

Tool benchTool(ToolShape shape) {
  Tool t;
  t.number = 1;
  t.shape = shape;
  t.diameter = 6.0;
  t.flute_length = 18.0;
  t.length = 60.0;
  t.shank_diameter = 6.0;
  if (shape == ToolShape::kBull) t.corner_radius = 1.0;
  if (shape == ToolShape::kDrill) t.tip_angle = 118.0;
  return t;
}

// Sweeps only the lowest 6 mm of the flutes' box, as a cut into a stock surface would.
Aabb lowerBox(const SweptVolume& s) {
  Aabb b = s.bounds();
  b.hi.z = std::min(b.hi.z, b.lo.z + 6.0);
  return b;
}

// Steps built per second (the per-step precomputation).
double buildRate(const ToolPart& part, const ToolPose& a, const ToolPose& b, double seconds) {
  long n = 0;
  double sink = 0;
  const auto start = Clock::now();
  double elapsed = 0;
  do {
    for (int i = 0; i < 100; ++i) {
      const SweptVolume s = SweptVolume::between(part, a, b, 0, 0.01);
      sink += s.bounds().hi.x;
    }
    n += 100;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < seconds);
  if (sink == 42.0) std::puts("");
  return n / elapsed;
}

// A 3-axis batch as the stock cuts it: 16 moves of 0.37 mm of `shape`'s cutter along
// a curved pass in x, and each move's own box (a body is asked on the lines its box
// holds: the (line, body) pairs).
struct Batch {
  SweptVolume sweep;
  std::vector<Aabb> boxes;
};

Batch batchOf(ToolShape shape) {
  const ToolPart part = makeToolPart(benchTool(shape), ToolPartKind::kCutter);
  std::vector<ToolPose> poses;
  for (int j = 0; j <= 16; ++j) {
    const double x = 0.37 * j;
    poses.push_back({{x, 0.2, 2.0 - 0.02 * x * x}, {0.0, 0.0, 1.0}});
  }
  Batch b{SweptVolume::chainOfTranslations(part, poses), {}};
  for (const Translation& t : b.sweep.translations())
    b.boxes.push_back(SweptVolume::chainOfTranslations(
                          part, std::vector<ToolPose>{{t.from, t.axis}, {t.to, t.axis}})
                          .bounds());
  return b;
}

// The z lines of a 3-axis batch, row by row against line by line.
void rowFigures(double seconds) {
  std::printf(
      "\n3-axis batch of 16 moves (0.37 mm each, a curved pass along x): z lines, "
      "rowIntervals (row by row) against lineIntervals (line by line)\n");
  std::printf("%-22s %7s %8s %10s %10s %10s %10s %7s\n", "tool", "lines", "pairs", "line ns",
              "row ns", "line ns/pr", "row ns/pr", "speedup");
  for (ToolShape shape : {ToolShape::kBall, ToolShape::kFlat, ToolShape::kDrill}) {
    const Batch batch = batchOf(shape);
    const SweptVolume& s = batch.sweep;
    const std::vector<Aabb>& boxes = batch.boxes;
    const Aabb b = s.bounds();
    std::vector<double> us;
    for (double u = std::floor(b.lo.x / kGrid) * kGrid; u <= b.hi.x; u += kGrid) us.push_back(u);
    std::vector<double> vs;
    for (double v = std::floor(b.lo.y / kGrid) * kGrid; v <= b.hi.y; v += kGrid) vs.push_back(v);
    const long lines = static_cast<long>(us.size() * vs.size());
    // Pairs: a body is asked on a line its box holds (the batch's bodies, one per move).
    long pairs = 0;
    for (const double v : vs)
      for (const double u : us)
        for (const Aabb& ob : boxes)
          pairs += u >= ob.lo.x && u <= ob.hi.x && v >= ob.lo.y && v <= ob.hi.y;
    std::vector<Interval> out;
    std::vector<std::size_t> ends(us.size());
    double lineNs = 1e300, rowNs = 1e300;
    for (int round = 0; round < 3; ++round) {
      for (int mode = 0; mode < 2; ++mode) {
        long done = 0;
        const auto start = Clock::now();
        double elapsed = 0;
        do {
          for (const double v : vs) {
            out.clear();
            if (mode == 0)
              for (const double u : us) s.lineIntervals(2, u, v, out);
            else
              s.rowIntervals(2, us, v, out, ends);
          }
          done += lines;
          elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        } while (elapsed < seconds / 6);
        double& best = mode == 0 ? lineNs : rowNs;
        best = std::min(best, 1e9 * elapsed / done);
      }
    }
    std::printf("%-22s %7ld %8ld %10.1f %10.1f %10.1f %10.1f %7.2f\n",
                std::string(toolShapeName(shape)).c_str(), lines, pairs, lineNs, rowNs,
                lineNs * lines / pairs, rowNs * lines / pairs, lineNs / rowNs);
  }
}

// The x and y lines of a 3-axis batch in its lowest 6 mm, in batches of ~1000 lines
// (what fastCut asks of a 32-step brick), against line by line.
void crossFigures(double seconds) {
  std::printf(
      "\nThe same batch: x and y lines of its lowest 6 mm, linesIntervals (batches of "
      "~1000 lines) against lineIntervals (line by line)\n");
  std::printf("%-22s %4s %7s %8s %10s %10s %10s %10s %7s\n", "tool", "dir", "lines", "pairs",
              "line ns", "batch ns", "line ns/pr", "batch ns/pr", "speedup");
  for (ToolShape shape : {ToolShape::kBall, ToolShape::kFlat, ToolShape::kDrill}) {
    const Batch batch = batchOf(shape);
    const SweptVolume& s = batch.sweep;
    const std::vector<Aabb>& boxes = batch.boxes;
    const Aabb b = s.bounds();
    for (int axis = 0; axis < 2; ++axis) {
      const int i1 = (axis + 1) % 3, i2 = (axis + 2) % 3;
      const auto range = [&](int i) {
        std::vector<double> c;
        const double top = i == 2 ? b.lo.z + 6.0 : b.hi[i];
        for (double x = std::floor(b.lo[i] / kGrid) * kGrid; x <= top; x += kGrid) c.push_back(x);
        return c;
      };
      std::vector<double> us, vs;
      for (const double v : range(i2))
        for (const double u : range(i1)) us.push_back(u), vs.push_back(v);
      const std::size_t lines = us.size();
      long pairs = 0;
      for (std::size_t i = 0; i < lines; ++i)
        for (const Aabb& ob : boxes)
          pairs +=
              us[i] >= ob.lo[i1] && us[i] <= ob.hi[i1] && vs[i] >= ob.lo[i2] && vs[i] <= ob.hi[i2];
      constexpr std::size_t kBatch = 1000;
      std::vector<Interval> out;
      std::vector<std::size_t> ends(kBatch);
      double lineNs = 1e300, batchNs = 1e300;
      for (int round = 0; round < 3; ++round)
        for (int mode = 0; mode < 2; ++mode) {
          long done = 0;
          const auto start = Clock::now();
          double elapsed = 0;
          do {
            for (std::size_t from = 0; from < lines; from += kBatch) {
              const std::size_t n = std::min(kBatch, lines - from);
              out.clear();
              if (mode == 0)
                for (std::size_t i = from; i < from + n; ++i)
                  s.lineIntervals(axis, us[i], vs[i], out);
              else
                s.linesIntervals(axis, std::span<const double>(us.data() + from, n),
                                 std::span<const double>(vs.data() + from, n), out,
                                 std::span<std::size_t>(ends.data(), n));
            }
            done += static_cast<long>(lines);
            elapsed = std::chrono::duration<double>(Clock::now() - start).count();
          } while (elapsed < seconds / 6);
          double& best = mode == 0 ? lineNs : batchNs;
          best = std::min(best, 1e9 * elapsed / done);
        }
      const double perPair = static_cast<double>(lines) / static_cast<double>(pairs);
      std::printf("%-22s %4c %7zu %8ld %10.1f %10.1f %10.1f %10.1f %7.2f\n",
                  std::string(toolShapeName(shape)).c_str(), "xy"[axis], lines, pairs, lineNs,
                  batchNs, lineNs * perPair, batchNs * perPair, lineNs / batchNs);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 0.5;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--seconds S]\n", argv[0]);
      return 2;
    }
  }
  if (!(seconds > 0)) {
    std::fprintf(stderr, "--seconds must be > 0\n");
    return 2;
  }

  // Baseline: a 3 mm sphere, the lines of its box, one ray-sphere solve each.
  const glm::dvec3 centre(0.03, 0.07, 3.01);
  const double r = 3.0;
  const std::vector<Line> sphereLines = gridLines(Aabb{centre - r, centre + r});
  const Rate base = measure(sphereLines, seconds, [&](const Line& l, std::vector<Interval>& out) {
    const int i1 = (l.axis + 1) % 3;
    const int i2 = (l.axis + 2) % 3;
    const double du = l.u - centre[i1];
    const double dv = l.v - centre[i2];
    const double h2 = r * r - du * du - dv * dv;
    if (h2 <= 0) return;
    const double h = std::sqrt(h2);
    out.push_back({centre[l.axis] - h, centre[l.axis] + h});
  });
  std::printf("grid %.2f mm, 6 mm tools (flutes 18), %.2f s per figure\n", kGrid, seconds);
  std::printf("baseline ray-sphere: %.1f ns per line (%zu lines, %.0f%% hit)\n",
              1e9 / base.callsPerSecond, sphereLines.size(), 100 * base.hitFraction);

  const ToolPose start{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  const ToolPose moved{{1.0, 0.4, -0.2}, {0.0, 0.0, 1.0}};
  const double tilt = 2.0 * std::acos(-1.0) / 180.0;  // 2 degrees in this step
  const ToolPose turned{{1.0, 0.4, -0.2}, {std::sin(tilt), 0.0, std::cos(tilt)}};
  // The same move with the axis held tilted 15 degrees: no closed form applies.
  const double t15 = 15.0 * std::acos(-1.0) / 180.0;
  const glm::dvec3 tilted(std::sin(t15), 0.0, std::cos(t15));
  const ToolPose tiltStart{start.tip, tilted};
  const ToolPose tiltMoved{moved.tip, tilted};
  struct Case {
    ToolShape shape;
    double cornerTolerance;
  };
  const Case cases[] = {{ToolShape::kBall, kDefaultCornerTolerance},
                        {ToolShape::kFlat, kDefaultCornerTolerance},
                        {ToolShape::kBull, kDefaultCornerTolerance},
                        {ToolShape::kBull, 0.01},
                        {ToolShape::kDrill, kDefaultCornerTolerance}};
  std::printf(
      "\nper line direction: lineIntervals (closed forms where the axis is a grid axis) "
      "against generalLineIntervals (the section solver for every body), same lines\n");
  std::printf("%-34s %4s %7s %9s %9s %7s %6s %9s\n", "case", "line", "lines", "fast ns",
              "general ns", "speedup", "hit", "steps/s");
  struct Move {
    const char* name;
    const ToolPose* a;
    const ToolPose* b;
  };
  const Move moves[] = {{"3-axis move 1.1 mm", &start, &moved},
                        {"tilted 15 deg move 1.1 mm", &tiltStart, &tiltMoved},
                        {"5-axis 2 deg", &start, &turned}};
  for (const Case& c : cases) {
    const ToolPart part =
        makeToolPart(benchTool(c.shape), ToolPartKind::kCutter, c.cornerTolerance);
    const std::string shape =
        std::string(toolShapeName(c.shape)) +
        (c.shape == ToolShape::kBull ? "(" + std::to_string(part.bodies[0].pieces.size()) + " pcs)"
                                     : "");
    for (const Move& m : moves) {
      const SweptVolume s = SweptVolume::between(part, *m.a, *m.b, 0, 0.01);
      const std::vector<Line> all = gridLines(lowerBox(s));
      const double steps = buildRate(part, *m.a, *m.b, seconds / 8);
      for (int axis = 0; axis < 3; ++axis) {
        std::vector<Line> lines;
        for (const Line& l : all)
          if (l.axis == axis) lines.push_back(l);
        // Alternating rounds, best of three each: load on a shared machine hits both alike.
        Rate fast, general;
        for (int round = 0; round < 3; ++round) {
          const Rate f =
              measure(lines, seconds / 9, [&](const Line& l, std::vector<Interval>& out) {
                s.lineIntervals(l.axis, l.u, l.v, out);
              });
          const Rate g =
              measure(lines, seconds / 9, [&](const Line& l, std::vector<Interval>& out) {
                s.generalLineIntervals(l.axis, l.u, l.v, out);
              });
          if (f.callsPerSecond > fast.callsPerSecond) fast = f;
          if (g.callsPerSecond > general.callsPerSecond) general = g;
        }
        std::string name = shape + " " + m.name;
        if (m.b == &turned) name += " " + std::to_string(s.translations().size()) + " sub";
        std::printf("%-34s %4c %7zu %9.1f %9.1f %7.2f %5.0f%% %9.3g\n", name.c_str(), "xyz"[axis],
                    lines.size(), 1e9 / fast.callsPerSecond, 1e9 / general.callsPerSecond,
                    fast.callsPerSecond / general.callsPerSecond, 100 * fast.hitFraction, steps);
      }
    }
  }
  rowFigures(seconds);
  crossFigures(seconds);
  return 0;
}

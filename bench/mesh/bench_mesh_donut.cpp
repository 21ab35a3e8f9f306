// Thesis table 6.7 recreated: the donut of figure 6.13 (table 6.8) cut into a
// 4 x 4 x 1 mm stock at each density with plain heightmaps and with 3-maps,
// meshed, and the largest closest-point error at a triangle centroid
// (equations 6.1-6.7) printed beside the thesis's. Also tables 6.9 and 6.10,
// stock memory, mesh size and meshing throughput.
//
//   bench_mesh [--densities 4,8,16,32,64] [--maps both|3way|plain]
//              [--steps 100] [--substeps 10] [--threads 2] [--check]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "bench/mesh/count_sink.h"
#include "bench/mesh/donut_surface.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool.h"
#include "sim/geometry/tool_part.h"
#include "sim/mdh/stock.h"
#include "sim/mesh/indexed_mesh.h"
#include "sim/mesh/mesher.h"
#include "sim/mesh/stock_view.h"

namespace {

using namespace mdhd;
using Clock = std::chrono::steady_clock;

// Table 6.7 of the thesis, by density.
const std::map<int, double> kThesisHeightmap{{4, 0.1586498},  {8, 0.0891680},  {16, 0.0601754},
                                             {32, 0.0383265}, {64, 0.0500396}, {128, 0.0086811}};
const std::map<int, double> kThesis3Map{{4, 0.1082255},  {8, 0.0278254},  {16, 0.0069804},
                                        {32, 0.0020188}, {64, 0.0005377}, {128, 0.0001459}};

struct Options {
  std::vector<int> densities{4, 8, 16, 32, 64};
  bool plain = true;
  bool threeWay = true;
  int steps = 100;
  int substeps = 10;
  int threads = 2;
  bool check = false;
};

struct Run {
  double error = 0.0;
  double cutSeconds = 0.0;
  double meshSeconds = 0.0;
  double meshSeconds2 = 0.0;  // on two threads (the same triangles)
  std::int64_t triangles = 0;
  std::int64_t machined = 0;  // triangles off the stock's boundary box
  std::size_t memory = 0;
  std::int64_t leaves = 0;
  std::int64_t splits = 0;
  std::int64_t forced = 0;  // vertices the engine dropped because no heightmap held them
  std::array<std::int64_t, 6> directions{};
  bool closed = true;
  std::int64_t fallback = 0;
};

// Counts triangles and takes the largest error at the machined triangles' centroids.
class ErrorSink final : public mesh::MeshSink {
 public:
  explicit ErrorSink(const mesh::bench::Donut& d) : donut_(d) {}
  void triangle(const mesh::MeshVertex& a, const mesh::MeshVertex& b, const mesh::MeshVertex& c,
                bool exterior) override {
    ++triangles;
    if (exterior) return;
    ++machined;
    maxError = std::max(maxError, donut_.error((a.position + b.position + c.position) / 3.0));
  }
  std::int64_t triangles = 0;
  std::int64_t machined = 0;
  double maxError = 0.0;

 private:
  const mesh::bench::Donut& donut_;
};

double seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

Run runOne(const Options& o, int density, bool threeWay) {
  const mesh::bench::Donut donut;
  mdh::StockOptions so;
  so.density = density;
  so.three_way = threeWay;
  so.threads = o.threads;
  mdh::Stock stock({{0, 0, 0}, {4, 4, 1}}, so);
  Run r;
  auto t0 = Clock::now();
  mesh::bench::cutDonut(stock, donut, o.steps, o.substeps);
  r.cutSeconds = seconds(t0);
  const mdh::Stats st = stock.stats();
  r.memory = st.memoryBytes;
  r.leaves = st.leaves;
  r.splits = st.splits();
  r.forced = st.forcedVertices;
  r.directions = st.directions;

  const mesh::StockView view(stock);
  mesh::bench::CountSink count;
  t0 = Clock::now();
  const mesh::MeshStats ms = mesh::meshStock(view, count);
  r.meshSeconds = seconds(t0);
  r.triangles = count.triangles;
  mesh::bench::CountSink count2;
  mesh::MeshOptions two;
  two.threads = 2;
  t0 = Clock::now();
  mesh::meshStock(view, count2, two);
  r.meshSeconds2 = seconds(t0);
  if (count2.triangles != count.triangles) r.closed = false;
  r.fallback = ms.fallbackCrossings;
  ErrorSink err(donut);
  mesh::meshStock(view, err);
  r.error = err.maxError;
  r.machined = err.machined;
  if (o.check) {
    mesh::IndexedMesh m;
    mesh::meshStock(view, m);
    r.closed = mesh::checkEdges(m).closed() && mesh::nonManifoldVertices(m) == 0;
  }
  return r;
}

std::vector<int> parseList(const std::string& s) {
  std::vector<int> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stoi(item));
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_mesh: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--densities")
      o.densities = parseList(value());
    else if (a == "--maps") {
      const std::string m = value();
      o.plain = m != "3way";
      o.threeWay = m != "plain";
    } else if (a == "--steps")
      o.steps = std::stoi(value());
    else if (a == "--substeps")
      o.substeps = std::stoi(value());
    else if (a == "--threads")
      o.threads = std::stoi(value());
    else if (a == "--check")
      o.check = true;
    else {
      std::fprintf(stderr,
                   "usage: bench_mesh [--densities 4,8,...] [--maps both|3way|plain] [--steps N] "
                   "[--substeps M] [--threads T] [--check]\n");
      std::exit(2);
    }
  }
  if (o.steps < 1 || o.substeps < 1) {
    std::fprintf(stderr, "bench_mesh: --steps and --substeps must be >= 1\n");
    std::exit(2);
  }
  return o;
}

double thesis(const std::map<int, double>& t, int d) {
  const auto it = t.find(d);
  return it == t.end() ? std::nan("") : it->second;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const mesh::bench::Donut donut;
  const double chord = 1.84 * (1 - std::cos(std::numbers::pi / (o.steps * o.substeps)));
  std::printf(
      "donut (thesis fig. 6.13, table 6.8): ball R %.2f, tilt %.0f deg, R_maj %.2f, P_T "
      "(%.0f, %.0f, %.4f), stock 4 x 4 x 1 mm\n",
      donut.radius, donut.tiltDegrees, donut.majorRadius, donut.centre.x, donut.centre.y,
      donut.centre.z);
  std::printf(
      "%d in-between steps (one cut each), each swept through a chain of %d poses; "
      "chord sagitta at the outer wall %.1e mm\n\n",
      o.steps, o.substeps, chord);
  std::map<int, Run> hm, tm;
  bool ok = true;
  std::printf("%7s %6s %8s %8s %10s %10s %10s %10s %7s %6s %6s %11s %11s\n", "density", "map",
              "cut s", "mesh s", "triangles", "tris/s", "2 thr", "memory KB", "leaves", "splits",
              "forced", "max error", "thesis");
  for (int d : o.densities) {
    for (int way = 0; way < 2; ++way) {
      const bool threeWay = way == 1;
      if ((threeWay && !o.threeWay) || (!threeWay && !o.plain)) continue;
      const Run r = runOne(o, d, threeWay);
      (threeWay ? tm : hm)[d] = r;
      std::printf(
          "%7d %6s %8.2f %8.3f %10lld %10.3g %10.3g %10.1f %7lld %6lld %6lld %11.7f %11.7f%s%s\n",
          d, threeWay ? "3-map" : "plain", r.cutSeconds, r.meshSeconds,
          static_cast<long long>(r.triangles), r.triangles / r.meshSeconds,
          r.triangles / r.meshSeconds2, r.memory / 1024.0, static_cast<long long>(r.leaves),
          static_cast<long long>(r.splits), static_cast<long long>(r.forced), r.error,
          thesis(threeWay ? kThesis3Map : kThesisHeightmap, d),
          o.check ? (r.closed ? "  closed" : "  NOT CLOSED") : "",
          r.fallback ? "  (cells disagree on shared vertices)" : "");
      std::fflush(stdout);
      if (o.check && !r.closed) ok = false;
      if (o.check && threeWay && r.error > thesis(kThesis3Map, d)) ok = false;
    }
  }
  std::printf("\nTable 6.7 (closest-point error, mm)\n%-22s", "stock density");
  for (int d : o.densities) std::printf(" %10d", d);
  auto row = [&](const char* name, auto value) {
    std::printf("\n%-22s", name);
    for (int d : o.densities) std::printf(" %10.7f", value(d));
  };
  if (o.plain) {
    row("heightmap (here)", [&](int d) { return hm[d].error; });
    row("heightmap (thesis)", [&](int d) { return thesis(kThesisHeightmap, d); });
  }
  if (o.threeWay) {
    row("3-map (here)", [&](int d) { return tm[d].error; });
    row("3-map (thesis)", [&](int d) { return thesis(kThesis3Map, d); });
  }
  std::printf("\n");
  if (o.plain && o.threeWay) {
    std::printf("\nTable 6.9 (heightmap at 2d over 3-map at d)\n%-30s", "densities");
    std::vector<int> pairs;
    for (int d : o.densities)
      if (hm.count(2 * d) && tm.count(d)) pairs.push_back(d);
    for (int d : pairs)
      std::printf(" %8s", (std::to_string(2 * d) + "/" + std::to_string(d)).c_str());
    std::printf("\n%-30s", "heightmap/3-map error");
    for (int d : pairs) std::printf(" %8.2f", hm[2 * d].error / tm[d].error);
    std::printf("\n%-30s", "heightmap/3-map memory");
    for (int d : pairs) std::printf(" %8.2f", double(hm[2 * d].memory) / tm[d].memory);
    std::printf("\n");
  }
  std::printf("\nTable 6.10 (error at d over error at 2d)\n%-22s", "densities");
  std::vector<int> steps;
  for (int d : o.densities)
    if ((hm.count(d) && hm.count(2 * d)) || (tm.count(d) && tm.count(2 * d))) steps.push_back(d);
  for (int d : steps)
    std::printf(" %8s", (std::to_string(d) + "/" + std::to_string(2 * d)).c_str());
  if (o.plain) {
    std::printf("\n%-22s", "heightmap");
    for (int d : steps) std::printf(" %8.2f", hm[d].error / hm[2 * d].error);
  }
  if (o.threeWay) {
    std::printf("\n%-22s", "3-map");
    for (int d : steps) std::printf(" %8.2f", tm[d].error / tm[2 * d].error);
  }
  std::printf("\n");
  if (o.check) std::printf("\ncheck: %s\n", ok ? "passed" : "FAILED");
  return ok ? 0 : 1;
}

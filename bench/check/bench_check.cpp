// Figures of mdhd check (issue 5): the FreeCAD peer's 3-axis dome (20,103 moves, 6 mm
// ball, 100 x 100 x 30 stock) and a 5-axis tilted-ball dome of the same size on an AC
// trunnion, at densities 5, 10 and 20: wall time, moves/s, peak memory (each run in a
// child process), cells, and the final mesh's worst error against the design surface.
// When freecadcmd is installed, FreeCAD's path simulator runs the same dome at the same
// grid spacing in the same run (peers/freecad/run_pathsim.py, hmap_from_stl.py).
//
//   bench_check [--densities 5,10,20] [--no-freecad] [--smoke] [--threads N] [--only 3|5]
//               [--passes K] [--first-pass J] [--batch B] [--plain] [--eager-crossings]
//               [--one-sided]
// --plain: plain heightmaps instead of 3-way ones (job option three_way false: no
// crossings on the edges across the map's direction, so no x and y lines to ask);
// --eager-crossings: every batch computes its crossings at once (lazy_crossings off);
// --one-sided: one-sided 3-maps (job option two_sided false);
// --batch: feed steps cut at once (check::SimulationOptions::batch_steps; 1: one by one);
// --threads: threads cutting and meshing the stock (default 1); --only: just the 3-axis
// or the 5-axis dome; --passes: only K zigzag passes (a slice for profiling; no FreeCAD
// run), from pass J (default 0: the dome's edge, where the walls are tall; the tool
// plunges into the uncut stock at the slice's start).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/check/dome_programs.h"
#include "protocol/stl.h"
#include "sim/check/simulation.h"
#include "sim/gcode/interpreter.h"
#include "sim/kinematics/presets.h"
#include "sim/mesh/mesher.h"

namespace {

using namespace mdhd;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

// Worst vertical distances of the machined surface's mesh from the design surface,
// inside the zigzag's area less a 3 mm border (as the peer's hmap_from_stl.py): at every
// vertex and at every triangle's centroid (where the thesis measures, 6.4), so that a
// chord sagging below the design between exact vertices counts.
class ErrorSink final : public mesh::MeshSink {
 public:
  ErrorSink(double cx, double cy) : cx_(cx), cy_(cy) {}
  void triangle(const mesh::MeshVertex& a, const mesh::MeshVertex& b, const mesh::MeshVertex& c,
                bool exterior) override {
    ++triangles_;
    if (exterior) return;
    const glm::dvec3 centroid = (a.position + b.position + c.position) / 3.0;
    for (const glm::dvec3* q : {&a.position, &b.position, &c.position, &centroid}) {
      const glm::dvec3& p = *q;
      if (std::abs(p.x - cx_) > 47.0 || std::abs(p.y - cy_) > 47.0 || p.z < 1.0) continue;
      const double err = p.z - bench::domeZ(p.x, p.y, cx_, cy_);
      overcut_ = std::max(overcut_, -err);
      undercut_ = std::max(undercut_, err);
    }
  }
  double overcut() const { return overcut_; }
  double undercut() const { return undercut_; }
  long triangles() const { return triangles_; }

 private:
  double cx_, cy_;
  double overcut_ = 0.0, undercut_ = 0.0;
  long triangles_ = 0;
};

// A stream buffer that counts what it is given and keeps none of it (seekable, so
// that the STL writer can patch its count).
class DiscardBuffer final : public std::streambuf {
 protected:
  int_type overflow(int_type c) override {
    ++at_;
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    at_ += n;
    return n;
  }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    return dir == std::ios_base::beg ? pos_type(off) : pos_type(at_ + off);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode) override { return pos; }

 private:
  std::streamsize at_ = 0;
};

struct Case {
  std::string name;
  kin::Machine machine;
  geom::Aabb stock;
  double cx = 50, cy = 50;
  std::string program;
  long moves = 0;
};

geom::Tool ballTool() {
  geom::Tool t;
  t.number = 1;
  t.shape = geom::ToolShape::kBall;
  t.diameter = 6;
  t.shank_diameter = 6;
  t.flute_length = 30;  // the dome is 20 mm deep; tilted 15 degrees the shank must clear
  t.length = 60;
  t.holder = {{25, 20}};
  return t;
}

// CPU seconds of this process so far, all threads.
double processCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_utime.tv_usec * 1e-6 + u.ru_stime.tv_sec +
         u.ru_stime.tv_usec * 1e-6;
}

// One run in this process at `density` with the command line's `options`: simulation,
// then the mesh into the error sink.
nlohmann::json simulate(const Case& c, double density, check::SimulationOptions options) {
  const kin::Kinematics kin(c.machine);
  const std::vector<geom::Tool> tools{ballTool()};
  options.density = density;
  const int threads = options.threads;
  const Clock::time_point t0 = Clock::now();
  check::Simulation sim(kin, tools, c.stock, {}, options);
  gcode::InterpreterConfig config;
  config.home = c.machine.home;
  config.axis_mask = 0;
  for (const kin::Joint& j : c.machine.joints)
    if (const auto a = kin::axisOfName(j.name)) config.axis_mask |= 1u << *a;
  config.tools.add({1, tools[0].length, tools[0].diameter});
  gcode::Interpreter interp(config, sim);
  interp.run(gcode::makeStringSource(c.program));
  const check::Report r = sim.finish(static_cast<std::int64_t>(interp.blocksExecuted()));
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  // The timed meshing makes what mdhd check writes (binary STL, into a stream that
  // keeps nothing); the errors come from a second, untimed meshing.
  DiscardBuffer discard;
  std::ostream nowhere(&discard);
  const Clock::time_point t1 = Clock::now();
  const double cpu1 = processCpuSeconds();
  mesh::MeshOptions meshOptions;
  meshOptions.threads = threads;  // as mdhd check meshes
  protocol::StlWriter stl(nowhere);
  mesh::meshStock(sim.stock(), stl, meshOptions);
  stl.finish();
  const double meshWall = std::chrono::duration<double>(Clock::now() - t1).count();
  const double meshCpu = processCpuSeconds() - cpu1;
  ErrorSink errors(c.cx, c.cy);
  mesh::meshStock(sim.stock(), errors, meshOptions);
  std::string first;
  if (!r.collisions.empty()) {
    const check::Collision& k = r.collisions.front();
    first = std::string(check::collisionTypeName(k.type)) + " at line " + std::to_string(k.line) +
            " (" + k.block + "), depth " + std::to_string(k.depth);
  }
  return {{"wall_s", wall},
          {"first_collision", first},
          {"moves", r.stats.moves.total()},
          {"steps", r.stats.steps},
          {"cells", r.mdh.cells},
          {"leaves", r.mdh.leaves},
          {"directions", r.mdh.directions},
          {"memory_bytes", r.mdh.memoryBytes},
          {"removed_mm3", r.stats.removed_volume_mm3},
          {"final_mm3", r.stats.final_volume_mm3},
          {"collisions", r.collisions.size()},
          {"mesh_s", meshWall},
          {"mesh_cpu_s", meshCpu},
          {"triangles", errors.triangles()},
          {"overcut_mm", errors.overcut()},
          {"undercut_mm", errors.undercut()},
          {"cut_ms", r.timing.cut_ms},
          {"probe_ms", r.timing.probe_ms},
          {"finish_ms", r.timing.finish_ms},
          {"batches", sim.cutBatchStats().batches},
          {"batched_steps", sim.cutBatchStats().steps},
          {"refused", sim.cutBatchStats().refused},
          {"overhang_events", r.mdh.overhangEvents},
          {"resamples", r.mdh.resamples},
          {"forced_cells", r.mdh.forcedCells},
          {"splits", r.mdh.splits()}};
}

// The run in a child process, so that its peak memory is its own.
nlohmann::json simulateInChild(const Case& c, double density,
                               const check::SimulationOptions& options) {
  int fds[2];
  if (pipe(fds) != 0) return {{"error", "pipe"}};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    std::string text;
    try {
      text = simulate(c, density, options).dump();
    } catch (const std::exception& e) {
      text = nlohmann::json{{"error", e.what()}}.dump();
    }
    const ssize_t n = write(fds[1], text.data(), text.size());
    _exit(n == static_cast<ssize_t>(text.size()) ? 0 : 1);
  }
  close(fds[1]);
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;)
    text.append(buf, static_cast<std::size_t>(n));
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  nlohmann::json j =
      text.empty() ? nlohmann::json{{"error", "child failed"}} : nlohmann::json::parse(text);
  j["peak_rss_mb"] = usage.ru_maxrss / 1024.0;
  // CPU seconds of the child: on a shared machine, the figure that load does not inflate.
  j["cpu_s"] = usage.ru_utime.tv_sec + usage.ru_utime.tv_usec * 1e-6 + usage.ru_stime.tv_sec +
               usage.ru_stime.tv_usec * 1e-6;
  return j;
}

std::string run(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    pclose(p);
  }
  return out;
}

// FreeCAD's PathSim on the peer's own dome file at grid spacing 1/density.
nlohmann::json freecad(const fs::path& work, const fs::path& gcode, double density) {
  const std::string peer = std::string(MDHD_SHARED_DIR) + "/peers/freecad";
  char res[32];
  std::snprintf(res, sizeof res, "%g", 1.0 / density);
  const fs::path json = work / ("fc_" + std::string(res) + ".json");
  const fs::path stl = work / ("fc_" + std::string(res) + ".stl");
  const fs::path wall = work / "fc_wall.txt";
  run("cd " + work.string() + " && /usr/bin/time -f '%e %M' -o " + wall.string() + " freecadcmd " +
      peer + "/run_pathsim.py gcode=" + gcode.string() + " res=" + res +
      " tool=ball json=" + json.string() + " out=" + stl.string() + " >/dev/null 2>&1");
  nlohmann::json out;
  std::ifstream in(json);
  if (!in) return {{"error", "freecadcmd produced no result"}};
  const nlohmann::json r = nlohmann::json::parse(in);
  // sim_total_s = setup + cutting + meshing (GetResultMesh): compared with mdhd's
  // run plus its meshing; without the meshing, with mdhd's run alone.
  out["sim_s"] = r.value("sim_total_s", 0.0);
  out["mesh_s"] = r.contains("times") ? r["times"].value("mesh_s", 0.0) : 0.0;
  out["peak_rss_mb"] = r.value("peak_rss_mb", 0.0);
  std::ifstream w(wall);
  double procWall = 0, procKb = 0;
  w >> procWall >> procKb;
  out["process_wall_s"] = procWall;
  const std::string hmap = run("cd " + work.string() + " && freecadcmd " + peer +
                               "/hmap_from_stl.py stl=" + stl.string() + " res=" + res +
                               " 2>/dev/null | grep -a '^HMAP '");
  if (hmap.size() > 5) {
    const nlohmann::json h = nlohmann::json::parse(hmap.substr(5));
    out["overcut_mm"] = -h.value("err_max_overcut", 0.0);
    out["undercut_mm"] = h.value("err_max_undercut", 0.0);
  }
  fs::remove(stl);
  return out;
}

std::vector<double> parseDensities(const std::string& s) {
  std::vector<double> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stod(item));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> densities{5, 10, 20};
  bool withFreecad = true, smoke = false;
  int only = 0, passes = -1, first = 0;
  check::SimulationOptions options;  // what the flags set; the density per run
  options.threads = 1;               // --threads' default here
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--densities" && i + 1 < argc)
      densities = parseDensities(argv[++i]);
    else if (a == "--no-freecad")
      withFreecad = false;
    else if (a == "--smoke")
      smoke = true;
    else if (a == "--threads" && i + 1 < argc)
      options.threads = std::atoi(argv[++i]);
    else if (a == "--only" && i + 1 < argc)
      only = std::atoi(argv[++i]);
    else if (a == "--passes" && i + 1 < argc)
      passes = std::atoi(argv[++i]);
    else if (a == "--first-pass" && i + 1 < argc)
      first = std::atoi(argv[++i]);
    else if (a == "--batch" && i + 1 < argc)
      options.batch_steps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--chain-tolerance" && i + 1 < argc)
      options.chain_tolerance = std::atof(argv[++i]);
    else if (a == "--brick-z" && i + 1 < argc)
      options.brick_z = std::atoi(argv[++i]);
    else if (a == "--plain")
      options.three_way = false;
    else if (a == "--eager-crossings")
      options.lazy_crossings = false;
    else if (a == "--one-sided")
      options.two_sided = false;
    else {
      std::fprintf(stderr,
                   "usage: bench_check [--densities 5,10,20] [--no-freecad] [--smoke] "
                   "[--threads N] [--only 3|5] [--passes K] [--first-pass J] [--batch B] [--plain] "
                   "[--brick-z Z] [--chain-tolerance T] [--eager-crossings] [--one-sided]\n");
      return 2;
    }
  }
  const int lines = smoke ? 8 : 100, pts = smoke ? 20 : 200;
  if (smoke) {
    densities = {2};
    withFreecad = false;
  }
  if (first < 0 || first >= lines) {
    std::fprintf(stderr, "bench_check: --first-pass must be in [0, %d)\n", lines);
    return 2;
  }
  if (passes >= 0 || first > 0) withFreecad = false;  // the peer runs the whole program
  std::vector<Case> cases;
  if (only != 5) {
    const bench::DomeProgram p = bench::domeProgram(lines, pts, true, passes, first);
    cases.push_back({"dome 3-axis",
                     kin::presets::threeAxisMill(),
                     {{0, 0, 0}, {100, 100, 30}},
                     50,
                     50,
                     p.text,
                     p.moves});
  }
  if (only != 3) {
    const kin::Machine m = kin::presets::acTrunnion();
    const kin::Kinematics kin(m);
    const bench::DomeProgram p =
        bench::tiltedDomeProgram(kin, ballTool().length, lines, pts, passes, first);
    cases.push_back({"dome 5-axis", m, {{-50, -50, 0}, {50, 50, 30}}, 0, 0, p.text, p.moves});
  }
  withFreecad = withFreecad && !run("command -v freecadcmd").empty();
  const fs::path work = fs::temp_directory_path() / ("bench_check_" + std::to_string(getpid()));
  fs::create_directories(work);
  const fs::path peerGcode = work / "dome20k.nc";
  std::ofstream(peerGcode) << bench::domeProgram(lines, pts, false).text;

  std::printf("%-12s %4s %8s %9s %8s %8s %9s %9s %8s %10s %10s %5s\n", "program", "dens", "moves",
              "wall_s", "cpu_s", "mesh_s", "moves/s", "peak_MB", "cells", "overcut", "undercut",
              "coll");
  int failures = 0;
  // The 3-axis dome's runs and FreeCAD's, for the accuracy-matched comparison.
  struct Run {
    double density, wall, overcut;
  };
  std::vector<Run> ours, peer;
  for (const Case& c : cases)
    for (double d : densities) {
      const nlohmann::json r = simulateInChild(c, d, options);
      if (r.contains("error")) {
        std::printf("%-12s %4g error: %s\n", c.name.c_str(), d,
                    r["error"].get<std::string>().c_str());
        ++failures;
        continue;
      }
      const double wall = r["wall_s"];
      std::printf("%-12s %4g %8lld %9.3f %8.3f %8.3f %9.0f %9.1f %8lld %10.4f %10.4f %5d\n",
                  c.name.c_str(), d, r["moves"].get<long long>(), wall, r["cpu_s"].get<double>(),
                  r["mesh_s"].get<double>(), r["moves"].get<double>() / wall,
                  r["peak_rss_mb"].get<double>(), r["cells"].get<long long>(),
                  r["overcut_mm"].get<double>(), r["undercut_mm"].get<double>(),
                  r["collisions"].get<int>());
      // Full precision, so runs can be compared bit for bit (threads, code changes).
      std::printf(
          "  final volume %.17g mm3, leaves %lld, cut %.0f ms, probes %.0f ms, finish %.0f ms, "
          "mesh "
          "CPU %.3f s, %lld triangles\n",
          r["final_mm3"].get<double>(), r["leaves"].get<long long>(), r["cut_ms"].get<double>(),
          r["probe_ms"].get<double>(), r["finish_ms"].get<double>(), r["mesh_cpu_s"].get<double>(),
          r["triangles"].get<long long>());
      std::printf("  cut batches %lld of %lld steps, %lld refused (cut again step by step)\n",
                  r["batches"].get<long long>(), r["batched_steps"].get<long long>(),
                  r["refused"].get<long long>());
      // How often a cut left the fast path (a cell's direction no longer held it).
      std::printf(
          "  slow path: %lld overhang events, %lld resamples, %lld splits, %lld forced cells\n",
          r["overhang_events"].get<long long>(), r["resamples"].get<long long>(),
          r["splits"].get<long long>(), r["forced_cells"].get<long long>());
      const auto& dirs = r["directions"];
      std::printf(
          "  partial leaves by direction: +x %lld, -x %lld, +y %lld, -y %lld, +z %lld, -z %lld\n",
          dirs[0].get<long long>(), dirs[1].get<long long>(), dirs[2].get<long long>(),
          dirs[3].get<long long>(), dirs[4].get<long long>(), dirs[5].get<long long>());
      if (c.name == "dome 3-axis") ours.push_back({d, wall, r["overcut_mm"].get<double>()});
      if (withFreecad && c.name == "dome 3-axis") {
        const nlohmann::json f = freecad(work, peerGcode, d);
        if (f.contains("error")) {
          std::printf("  FreeCAD   %4g error: %s\n", d, f["error"].get<std::string>().c_str());
          continue;
        }
        const double fsim = f["sim_s"], fmesh = f["mesh_s"], fmb = f["peak_rss_mb"];
        const double mesh = r["mesh_s"];
        std::printf(
            "  FreeCAD   %4g sim %.3f s (meshing %.3f s of it; process %.2f s), peak %.1f MB, "
            "over-cut %.4f, under-cut %.4f\n",
            d, fsim, fmesh, f["process_wall_s"].get<double>(), fmb, f.value("overcut_mm", NAN),
            f.value("undercut_mm", NAN));
        std::printf(
            "  ratio     %4g wall FreeCAD/mdhd %.2f without meshing, %.2f with it; peak memory "
            "mdhd/FreeCAD %.2f, over-cut FreeCAD/mdhd %.1f\n",
            d, (fsim - fmesh) / wall, fsim / (wall + mesh), r["peak_rss_mb"].get<double>() / fmb,
            f.value("overcut_mm", NAN) / std::max(1e-9, r["overcut_mm"].get<double>()));
        peer.push_back({d, fsim - fmesh, f.value("overcut_mm", NAN)});
      }
      if (!r["first_collision"].get<std::string>().empty())
        std::printf("  first collision: %s\n", r["first_collision"].get<std::string>().c_str());
      std::fflush(stdout);
    }
  if (!withFreecad && !smoke)
    std::printf("(FreeCAD not run: freecadcmd not found or --no-freecad)\n");
  // Beside the same-spacing ratios: FreeCAD at each spacing against the coarsest mdhd run
  // of this bench that is at least ten times more accurate (over-cut), simulation only.
  for (const Run& f : peer) {
    const Run* best = nullptr;
    for (const Run& o : ours)
      if (o.overcut * 10 <= f.overcut && (best == nullptr || o.density < best->density)) best = &o;
    if (best != nullptr)
      std::printf(
          "accuracy-matched: FreeCAD at %g/mm (over-cut %.4f mm) against mdhd at %g/mm (%.4f mm, "
          "%.0fx more accurate): wall FreeCAD/mdhd %.2f\n",
          f.density, f.overcut, best->density, best->overcut,
          f.overcut / std::max(1e-9, best->overcut), f.wall / best->wall);
  }
  fs::remove_all(work);
  return failures == 0 ? 0 : 1;
}

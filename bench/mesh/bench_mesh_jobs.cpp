// Meshing throughput and mesh size for the example jobs: each job in
// ../shared/examples is checked as `mdhd check` would (its own density), the
// final stock meshed into a counting sink (best of `--repeat` runs, on one
// thread and on two) and into an indexed mesh to check it is closed. STL size
// = 84 + 50 bytes per triangle.
//
//   bench_mesh_jobs [--examples DIR] [--repeat N] [--smoke]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/mesh/count_sink.h"
#include "daemon/check_runner.h"
#include "sim/mesh/indexed_mesh.h"
#include "sim/mesh/mesher.h"
#include "sim/mesh/stock_view.h"

namespace {

using namespace mdhd;
using Clock = std::chrono::steady_clock;

struct Measured {
  double cutSeconds = 0.0, meshSeconds = 0.0, meshSeconds2 = 0.0;  // 1 and 2 threads
  std::int64_t triangles = 0, leaves = 0, fallback = 0;
  bool closed = false;
};

Measured measure(const std::filesystem::path& job, int repeat) {
  Measured out;
  const cli::LoadedJob loaded = cli::loadCheckedJobFile(job);
  cli::CheckControls controls;
  controls.finished = [&](const mdh::Stock& stock) {
    const mesh::StockView view(stock);
    out.meshSeconds = 1e30;
    for (int r = 0; r < repeat; ++r) {
      mesh::bench::CountSink count;
      const auto t0 = Clock::now();
      const mesh::MeshStats s = mesh::meshStock(view, count);
      out.meshSeconds =
          std::min(out.meshSeconds, std::chrono::duration<double>(Clock::now() - t0).count());
      out.triangles = count.triangles;
      out.leaves = s.leaves;
      out.fallback = s.fallbackCrossings;
    }
    out.meshSeconds2 = 1e30;
    mesh::MeshOptions two;
    two.threads = 2;
    for (int r = 0; r < repeat; ++r) {
      mesh::bench::CountSink count;
      const auto t0 = Clock::now();
      mesh::meshStock(view, count, two);
      out.meshSeconds2 =
          std::min(out.meshSeconds2, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    mesh::IndexedMesh m;
    mesh::meshStock(view, m);
    out.closed = mesh::checkEdges(m).closed() && mesh::nonManifoldVertices(m) == 0;
  };
  const auto t0 = Clock::now();
  const check::Report report = cli::runCheckJob(loaded, controls);
  // The check's wall time includes the meshing done in `finished`.
  out.cutSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (report.status == check::Status::kError) {
    std::fprintf(stderr, "bench_mesh_jobs: %s: the check failed\n", job.string().c_str());
    std::exit(1);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path dir = MDHD_SHARED_DIR "/examples";
  int repeat = 3;
  bool smoke = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--examples" && i + 1 < argc)
      dir = argv[++i];
    else if (a == "--repeat" && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--smoke")
      smoke = true;
    else {
      std::fprintf(stderr, "usage: bench_mesh_jobs [--examples DIR] [--repeat N] [--smoke]\n");
      return 2;
    }
  }
  std::vector<std::filesystem::path> jobs;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".json" && name.rfind("machine-", 0) != 0) jobs.push_back(e.path());
  }
  std::sort(jobs.begin(), jobs.end());
  // The smoke run (ctest) meshes the small 3-axis jobs only.
  if (smoke)
    jobs.erase(std::remove_if(jobs.begin(), jobs.end(),
                              [](const auto& p) {
                                return p.filename().string().find("3axis") == std::string::npos;
                              }),
               jobs.end());
  std::printf("%-20s %8s %10s %8s %10s %10s %10s %9s %7s\n", "job", "check s", "triangles",
              "mesh s", "tris/s", "2 thr", "STL MB", "leaves", "closed");
  bool ok = !jobs.empty();
  for (const auto& job : jobs) {
    const Measured m = measure(job, repeat);
    std::printf("%-20s %8.2f %10lld %8.4f %10.3g %10.3g %10.2f %9lld %7s\n",
                job.stem().string().c_str(), m.cutSeconds, static_cast<long long>(m.triangles),
                m.meshSeconds, m.triangles / m.meshSeconds, m.triangles / m.meshSeconds2,
                (84.0 + 50.0 * m.triangles) / 1e6, static_cast<long long>(m.leaves),
                m.closed && m.fallback == 0 ? "yes" : "NO");
    std::fflush(stdout);
    ok = ok && m.closed && m.fallback == 0 && m.triangles > 0;
  }
  return ok ? 0 : 1;
}

// Throughput of the common case: 3-axis slotting with a ball end mill
// (r = 3 mm, 5 mm deep, 0.5 mm in-between steps) across a 100 x 80 x 40 mm
// stock. Prints CPU and wall time per step.
//   mdh_raster [density=10] [brick=32] [threads=1] [passes=6]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "sim/mdh/stock.h"
#include "tests/mdh/analytic_solids.h"

using namespace mdhd::mdh;

int main(int argc, char** argv) {
  StockOptions o;
  o.density = argc > 1 ? std::atof(argv[1]) : 10.0;
  o.brick = argc > 2 ? std::atoi(argv[2]) : 32;
  o.threads = argc > 3 ? std::atoi(argv[3]) : 1;
  const int passes = argc > 4 ? std::atoi(argv[4]) : 6;
  Stock stock({{0, 0, 0}, {100, 80, 40}}, o);
  stock.setToolRadius(3.0);
  int steps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (int p = 0; p < passes; ++p)
    for (double x = 0; x <= 100; x += 0.5) {
      const double y = 5.0 + 4.0 * p;
      const testing::CapsuleSolid tool({x, y, 35}, {x, y, 80}, 3.0);
      stock.cut(tool, {0, 0, 1});
      ++steps;
    }
  const double cpu = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
  const double wall =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const Stats s = stock.stats();
  std::printf(
      "density %.0f brick %d threads %d: %d steps, %.3f ms CPU/step, %.3f ms wall/step, "
      "volume %.1f mm3, leaves %lld, memory %.1f MB, %.2f %% of pointer grid\n",
      o.density, o.brick, o.threads, steps, cpu / steps, wall / steps, stock.volume(),
      (long long)s.leaves, s.memoryBytes / 1e6, s.pointerGridPercent);
  return 0;
}

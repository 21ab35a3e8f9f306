// Reads a generated CAM-style program (`G1 X12.345 Y-6.789 Z-1.5 F800` lines)
// from a file through the Reader and prints lines/s, plus the peak memory, to
// show that reading streams (memory does not grow with the program).
//
//   bench_gcode_reader [lines=1000000] [path=/tmp/mdhd_bench_reader.ngc]
#include <sys/resource.h>
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "sim/gcode/reader.h"

namespace {

void writeProgram(const std::string& path, long lines) {
  std::ofstream out(path, std::ios::binary);
  out << "G21 G90 G17 G94\n";
  char line[96];
  for (long i = 1; i < lines; ++i) {
    // Varying values so number parsing is really exercised.
    const double x = static_cast<double>(i % 100000) * 0.001 + 12.345;
    const double y = -static_cast<double>(i % 7919) * 0.001 - 6.789;
    const double z = -static_cast<double>(i % 37) * 0.1 - 1.5;
    std::snprintf(line, sizeof line, "G1 X%.3f Y%.3f Z%.3f F800\n", x, y, z);
    out << line;
  }
}

// CPU time of this process: on a shared, loaded machine wall time mostly
// measures the other processes.
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

long peakRssKb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mdhd::gcode;
  const long lines = argc > 1 ? std::atol(argv[1]) : 1'000'000;
  const std::string path = argc > 2 ? argv[2] : "/tmp/mdhd_bench_reader.ngc";
  writeProgram(path, lines);

  ParameterStore params;
  Reader reader(makeStreamSource(std::make_unique<std::ifstream>(path, std::ios::binary)), params);
  Block block;
  long blocks = 0;
  double checksum = 0.0;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = cpuSeconds();
  while (reader.next(block)) {
    ++blocks;
    checksum += block.words.back().value;
  }
  const double cpu = cpuSeconds() - cpu_start;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double n = static_cast<double>(lines);
  std::printf(
      "reader: %ld blocks, CPU %.3f s = %.0f lines/s (%.0f ns/line); wall %.3f s = %.0f "
      "lines/s; peak RSS %ld KiB; checksum %.3f\n",
      blocks, cpu, n / cpu, cpu * 1e9 / n, wall, n / wall, peakRssKb(), checksum);
  std::remove(path.c_str());
  return blocks == lines ? 0 : 1;
}

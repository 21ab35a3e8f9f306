// Writes a CAM-like program (G1 X Y Z F, some G2/G3, comments, a few M codes)
// to a temp file and interprets it streaming into a null sink. Prints blocks/s,
// peak RSS after a small and a large run (memory must not grow with length),
// and the time of just reading the lines with std::getline as a baseline.
//   bench_gcode_interp [small_lines=100000] [large_lines=1000000]
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/gcode/interpreter.h"
#include "sim/gcode/source.h"

namespace {

using mdhd::gcode::Interpreter;
using mdhd::gcode::InterpreterConfig;

struct NullSink : mdhd::gcode::MotionSink {
  unsigned long motions = 0;
  double checksum = 0.0;
  void motion(const mdhd::gcode::Motion& m) override {
    ++motions;
    checksum += m.end[0];
  }
};

void writeProgram(const std::string& path, long lines) {
  std::ofstream out(path);
  out << "(bench program)\nG21 G90 G17 G94\nT1 M6\nG43 H1\nS10000 M3\nM8\nG0 X0 Y0 Z5\n";
  char buf[128];
  double x = 0, y = 0;
  for (long i = 0; i < lines - 9; ++i) {
    const long k = i % 100;
    if (k == 0) {
      out << "(pass " << i / 100 << ")\n";
    } else if (k == 50) {
      // a half circle of radius 2 and back
      std::snprintf(buf, sizeof buf, "G2 X%.4f Y%.4f I2 J0\n", x + 4, y);
      out << buf;
      x += 4;
    } else if (k == 51) {
      std::snprintf(buf, sizeof buf, "G3 X%.4f Y%.4f I-2 J0\n", x - 4, y);
      out << buf;
      x -= 4;
    } else {
      x = 50.0 * std::sin(i * 0.001);
      y = 50.0 * std::cos(i * 0.0007);
      const double z = -1.0 - 0.5 * std::sin(i * 0.01);
      std::snprintf(buf, sizeof buf, "G1 X%.4f Y%.4f Z%.4f F%d\n", x, y, z,
                    static_cast<int>(1000 + (k % 7) * 100));
      out << buf;
    }
  }
  out << "M9\nM30\n";
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

long peakRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

void measure(long lines) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("mdhd_bench_" + std::to_string(lines) + ".ngc"))
          .string();
  writeProgram(path, lines);
  auto t0 = std::chrono::steady_clock::now();
  long read = 0;
  {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) ++read;
  }
  const double t_read = seconds(t0);
  InterpreterConfig config;
  config.tools.add({1, 50.0, 6.0});
  NullSink sink;
  Interpreter interp(config, sink);
  t0 = std::chrono::steady_clock::now();
  interp.run(mdhd::gcode::makeStreamSource(std::make_unique<std::ifstream>(path)));
  const double t_run = seconds(t0);
  std::filesystem::remove(path);
  const double blocks = static_cast<double>(interp.blocksExecuted());
  std::printf(
      "lines %ld: %.0f blocks in %.3f s = %.2f M blocks/s; getline only %.3f s (ratio %.1fx); "
      "motions %lu; peak RSS %ld kB\n",
      lines, blocks, t_run, blocks / t_run / 1e6, t_read, t_run / t_read, sink.motions,
      peakRssKb());
}

}  // namespace

int main(int argc, char** argv) {
  const long small = argc > 1 ? std::atol(argv[1]) : 100000;
  const long large = argc > 2 ? std::atol(argv[2]) : 1000000;
  if (small < 20 || large < 20) {
    std::fprintf(stderr, "line counts must be at least 20\n");
    return 2;
  }
  try {
    measure(small);
    measure(large);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}

// Prints the figures of thesis chapter 6 for our recreation of its eleven
// examples: subdivision counts per ruleset (table 6.2), split-type shares,
// memory metrics (table 6.6) and run times, single root cell and bricks,
// one and two threads.
//   mdh_thesis_cases [density=10] [stamps_per_mm=10]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "bench/mdh/thesis_cases.h"
#include "sim/mdh/stock.h"

using namespace mdhd::mdh;

namespace {

struct Run {
  Stats stats;
  double ms = 0;     // wall clock
  double cpuMs = 0;  // process CPU time (all threads): comparable on a loaded machine
  double volume = 0;
};

Run run(const bench::ThesisCase& c, std::vector<Rule> rules, double density, int brick,
        int threads) {
  StockOptions o;
  o.density = density;
  o.ruleset = std::move(rules);
  o.brick = brick;
  o.threads = threads;
  Stock stock(c.stock, o);
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (const auto& s : c.steps) {
    stock.setToolRadius(s.radius);
    stock.cut(*s.solid, s.direction);
  }
  Run r;
  r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.cpuMs = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
  r.stats = stock.stats();
  r.volume = stock.volume();
  return r;
}

std::string rulesName(const std::vector<Rule>& rules) {
  std::string s;
  for (Rule r : rules) s += (s.empty() ? "" : ",") + std::string(ruleName(r));
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const double density = argc > 1 ? std::atof(argv[1]) : 10.0;
  const double perMm = argc > 2 ? std::atof(argv[2]) : 10.0;
  const auto cases = bench::thesisCases(perMm);
  using R = Rule;
  const std::vector<std::vector<Rule>> rulesets = {
      {R::kRS},
      {R::kCTD, R::kRS},
      {R::kSPT, R::kRS},
      {R::kFFS, R::kRS},
      {R::kFFS, R::kSPT, R::kCTD, R::kRS},
      {R::kFEFS, R::kRS},
      {R::kFEFS, R::kCTD, R::kSPT, R::kRS},
      {R::kFEFS, R::kSPT, R::kCTD, R::kRS},
      {R::kFEFS_FFS, R::kRS},
      {R::kFEFS_FFS, R::kCTD, R::kSPT, R::kRS},
      {R::kFEFS_FFS, R::kSPT, R::kCTD, R::kRS},
      {R::kSPT, R::kFEFS_FFS, R::kCTD, R::kRS},
  };
  std::printf("density %.0f/mm, %.0f stamps/mm, stock 10 mm cube, one root cell (brick 0)\n\n",
              density, perMm);
  std::printf("Subdivisions per ruleset (table 6.2)\n%-26s", "ruleset");
  for (const auto& c : cases) std::printf("%7s", c.name.c_str());
  std::printf("\n%-26s", "steps");
  for (const auto& c : cases) std::printf("%7zu", c.steps.size());
  std::printf("\n");
  for (const auto& rules : rulesets) {
    std::printf("%-26s", rulesName(rules).c_str());
    for (const auto& c : cases)
      std::printf("%7lld", (long long)run(c, rules, density, 0, 1).stats.splits());
    std::printf("\n");
  }
  const std::vector<Rule> best{R::kFEFS_FFS, R::kCTD, R::kSPT, R::kRS};
  std::printf("\nRuleset %s, brick 0, 1 thread (tables 6.5, 6.6)\n", rulesName(best).c_str());
  std::printf("%-5s %6s %6s %6s %6s %6s %6s %8s %9s %8s %8s %9s\n", "case", "splits", "direct",
              "indir", "sign", "fallbk", "forced", "leaves", "memory_kB", "%ptrgrid", "%embed",
              "cpu_ms");
  double shares[3] = {0, 0, 0};
  int counted = 0;
  for (const auto& c : cases) {
    const Run r = run(c, best, density, 0, 1);
    const Stats& s = r.stats;
    const double embeddedBytes = 8.0 * s.embeddedSamples;
    std::printf("%-5s %6lld %6lld %6lld %6lld %6lld %6lld %8lld %9.1f %8.2f %8.2f %9.1f\n",
                c.name.c_str(), (long long)s.splits(), (long long)s.splitsDirect,
                (long long)s.splitsIndirect, (long long)s.splitsSignConflict,
                (long long)s.splitsFallback, (long long)s.forcedVertices, (long long)s.leaves,
                s.memoryBytes / 1024.0, s.pointerGridPercent,
                100.0 * embeddedBytes / double(s.memoryBytes), r.cpuMs);
    const double thesisTyped = double(s.splitsDirect + s.splitsIndirect + s.splitsSignConflict);
    if (thesisTyped > 0) {
      shares[0] += s.splitsIndirect / thesisTyped;
      shares[1] += s.splitsDirect / thesisTyped;
      shares[2] += s.splitsSignConflict / thesisTyped;
      ++counted;
    }
  }
  if (counted > 0)
    std::printf(
        "\nSplit-type shares, mean over cases with splits (thesis: 40.2 %% indirect, "
        "44.8 %% direct, 14.9 %% sign conflict): %.1f %% indirect, %.1f %% direct, "
        "%.1f %% sign conflict\n",
        100 * shares[0] / counted, 100 * shares[1] / counted, 100 * shares[2] / counted);
  std::printf(
      "\nRun time by layout, ruleset %s: CPU ms (one thread) and wall ms\n"
      "%-5s %10s %10s %10s %10s  %s\n",
      rulesName(best).c_str(), "case", "cpu_b0", "cpu_b32", "wall_b32x1", "wall_b32x2",
      "same result 1 vs 2 threads");
  for (const auto& c : cases) {
    const Run a = run(c, best, density, 0, 1);
    const Run b = run(c, best, density, 32, 1);
    const Run d = run(c, best, density, 32, 2);
    std::printf("%-5s %10.1f %10.1f %10.1f %10.1f  %s\n", c.name.c_str(), a.cpuMs, b.cpuMs, b.ms,
                d.ms, b.volume == d.volume && b.stats.splits() == d.stats.splits() ? "yes" : "NO");
  }
  return 0;
}

// The figures of thesis chapter 6 for our recreation of its eleven examples as
// real tool motions (swept volumes of the flutes), one root cell (brick 0):
// subdivisions per ruleset beside table 6.2, split-type shares, the memory
// metrics of table 6.6 beside the thesis's, and CPU time. RS is seeded: each
// ruleset runs with seeds 1..N and prints min and (upper) median.
//   mdh_thesis_cases [--density 100] [--seeds 3] [--rulesets few|table66|all]
//                    [--ruleset FEFS-FFS,CTD,SPT,RS]... [--cases CS,D1,...]
//                    [--cuts-per-motion 1] [--degrees-per-motion 5] [--one-sided] [--smoke]
// --ruleset R (repeatable) runs the named rulesets instead of --rulesets.
// --cuts-per-motion k: each motion cut as k swept pieces (10 = the thesis's
// in-between steps as separate cuts; 1 = one swept volume per motion).
// --degrees-per-motion a: the turn of one motion of D1, D2, DS1, DS2 (lost with
// the thesis's figures; a calibration knob like DS's pitch).
// --one-sided: one-sided 3-maps, the thesis's own (StockOptions::two_sided off; two-sided
// maps, thesis 7.4, are the default: a sign conflict alone splits no cell).
// --smoke: density 25, one seed, three rulesets; exits 1 if a result is wrong.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "bench/mdh/thesis_cases.h"
#include "bench/mdh/thesis_reference.h"
#include "sim/geometry/pose_interpolation.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_part.h"
#include "sim/mdh/stock.h"

using namespace mdhd;
using namespace mdhd::mdh;

namespace {

constexpr int kInBetweenSteps = 10;  // table 6.1

struct Prepared {
  bench::ThesisCase c;
  std::vector<geom::SweptVolume> sweeps;
  std::vector<glm::dvec3> axes;
};

struct Run {
  Stats stats;
  double cpuS = 0;
  double volume = 0;
  double boxVolume = 0;
};

Prepared prepare(bench::ThesisCase c, int cutsPerMotion) {
  Prepared p{std::move(c), {}, {}};
  const geom::ToolPart part = geom::makeToolPart(p.c.tool, geom::ToolPartKind::kCutter);
  for (const auto& m : p.c.motions) {
    if (cutsPerMotion <= 1) {
      p.sweeps.push_back(geom::SweptVolume::between(part, m.a, m.b, kInBetweenSteps, 1e-3));
      p.axes.push_back(glm::normalize(m.a.axis + m.b.axis));
      continue;
    }
    // Each in-between step its own cut, as the thesis stamped them.
    geom::ToolPose from = m.a;
    for (int i = 1; i <= cutsPerMotion; ++i) {
      const geom::ToolPose to = geom::interpolatePose(m.a, m.b, double(i) / cutsPerMotion);
      p.sweeps.push_back(geom::SweptVolume::between(part, from, to, 1, 1e-3));
      p.axes.push_back(glm::normalize(from.axis + to.axis));
      from = to;
    }
  }
  return p;
}

Run run(const Prepared& p, const std::vector<Rule>& rules, double density, std::uint64_t seed,
        bool twoSided) {
  StockOptions o;
  o.two_sided = twoSided;
  o.density = density;
  o.ruleset = rules;
  o.brick = 0;
  o.threads = 1;
  o.seed = seed;
  o.tool_radius_hint = p.c.tool.radius();
  Stock stock(p.c.stock, o);
  const std::clock_t c0 = std::clock();
  for (std::size_t i = 0; i < p.sweeps.size(); ++i) stock.cut(p.sweeps[i], p.axes[i]);
  Run r;
  r.cpuS = double(std::clock() - c0) / CLOCKS_PER_SEC;
  r.stats = stock.stats();
  r.volume = stock.volume();
  const glm::dvec3 e = p.c.stock.hi - p.c.stock.lo;
  r.boxVolume = e.x * e.y * e.z;
  stock.checkInvariants();
  return r;
}

std::optional<std::vector<Rule>> parseRules(std::string_view s) {
  std::vector<Rule> out;
  while (!s.empty()) {
    const auto comma = s.find(',');
    const auto rule = ruleFromName(s.substr(0, comma));
    if (!rule) return std::nullopt;
    out.push_back(*rule);
    s = comma == std::string_view::npos ? std::string_view{} : s.substr(comma + 1);
  }
  if (out.empty()) return std::nullopt;
  return out;
}

// Runs of one ruleset on one case, sorted by subdivision count.
using Runs = std::vector<Run>;
const Run& median(const Runs& r) {
  return r[r.size() / 2];  // the upper median: with two seeds, the worse one
}

void printRatio(double ours, double thesis) {
  if (thesis > 0)
    std::printf("%8.2f", ours / thesis);
  else
    std::printf("%8s", "-");
}

}  // namespace

int main(int argc, char** argv) {
  double density = 100;
  int seeds = 3;
  std::string rulesetChoice = "few", caseFilter;
  std::vector<std::string> named;
  bool smoke = false;
  bool twoSided = true;
  int cutsPerMotion = 1;
  double donutDegrees = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--density")
      density = std::atof(next), ++i;
    else if (a == "--seeds")
      seeds = std::atoi(next), ++i;
    else if (a == "--rulesets")
      rulesetChoice = next, ++i;
    else if (a == "--ruleset")
      named.emplace_back(next), ++i;
    else if (a == "--cases")
      caseFilter = "," + std::string(next) + ",", ++i;
    else if (a == "--cuts-per-motion")
      cutsPerMotion = std::atoi(next), ++i;
    else if (a == "--degrees-per-motion")
      donutDegrees = std::atof(next), ++i;
    else if (a == "--smoke")
      smoke = true;
    else if (a == "--one-sided")
      twoSided = false;
    else {
      std::fprintf(stderr, "mdh_thesis_cases: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  if (smoke) density = 25, seeds = 1, rulesetChoice = "few";
  if (!(density > 0) || seeds < 1 || !(donutDegrees > 0 && donutDegrees <= 360)) {
    std::fprintf(stderr,
                 "mdh_thesis_cases: --density must be > 0, --seeds >= 1 and "
                 "--degrees-per-motion in (0, 360]\n");
    return 2;
  }
  for (const std::string& r : named)
    if (!parseRules(r)) {
      std::fprintf(stderr, "mdh_thesis_cases: unknown rule in --ruleset '%s'\n", r.c_str());
      return 2;
    }
  std::vector<std::string> rulesets = named;
  if (named.empty()) {
    if (rulesetChoice == "all")
      for (const auto& r : bench::kTable62) rulesets.emplace_back(r.rules);
    else if (rulesetChoice == "table66")
      for (const auto& r : bench::kTable66) rulesets.emplace_back(r.rules);
    else
      rulesets = {"RS", "FFS,RS", "FEFS-FFS,CTD,SPT,RS"};
    if (rulesetChoice == "few" && !smoke) rulesets.push_back("FEFS-FFS,SPT,CTD,RS");
  }

  std::vector<Prepared> cases;
  std::vector<int> thesisIndex;
  {
    const auto all = bench::thesisCases(donutDegrees);
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (!caseFilter.empty() && caseFilter.find("," + all[i].name + ",") == std::string::npos)
        continue;
      cases.push_back(prepare(all[i], cutsPerMotion));
      thesisIndex.push_back(static_cast<int>(i));
    }
  }
  std::printf(
      "density %g/mm, %d in-between steps per motion, brick 0 (one root cell), 1 thread, "
      "seeds 1..%d\n\ncase  stock_mm        tool      motions  guessed\n",
      density, kInBetweenSteps, seeds);
  for (const auto& p : cases) {
    const glm::dvec3 e = p.c.stock.hi - p.c.stock.lo;
    std::printf("%-5s %-15s %-4s r=%.2f %6zu   %s\n", p.c.name.c_str(),
                (std::to_string(e.x).substr(0, 3) + "x" + std::to_string(e.y).substr(0, 3) + "x" +
                 std::to_string(e.z).substr(0, 3))
                    .c_str(),
                std::string(geom::toolShapeName(p.c.tool.shape)).c_str(), p.c.tool.radius(),
                p.c.motions.size(), p.c.guess.c_str());
  }

  // results[ruleset][case]: runs sorted by subdivisions
  std::vector<std::vector<Runs>> results(rulesets.size(), std::vector<Runs>(cases.size()));
  bool ok = true;
  for (std::size_t r = 0; r < rulesets.size(); ++r)
    for (std::size_t c = 0; c < cases.size(); ++c) {
      Runs& runs = results[r][c];
      for (int s = 1; s <= seeds; ++s) {
        runs.push_back(
            run(cases[c], *parseRules(rulesets[r]), density, std::uint64_t(s), twoSided));
        const Run& x = runs.back();
        if (!(x.volume > 0 && x.volume < x.boxVolume) || !std::isfinite(x.volume)) {
          std::printf("FAIL %s %s: volume %g of %g\n", cases[c].c.name.c_str(), rulesets[r].c_str(),
                      x.volume, x.boxVolume);
          ok = false;
        }
      }
      std::sort(runs.begin(), runs.end(),
                [](const Run& a, const Run& b) { return a.stats.splits() < b.stats.splits(); });
    }

  std::printf(
      "\nSubdivisions per ruleset (table 6.2): min and upper median over seeds, thesis, "
      "median/thesis\n%-21s %-6s",
      "ruleset", "");
  for (const auto& p : cases) std::printf("%8s", p.c.name.c_str());
  std::printf("\n");
  for (std::size_t r = 0; r < rulesets.size(); ++r) {
    const auto thesis = bench::thesisSubdivisions(rulesets[r]);
    std::printf("%-21s %-6s", rulesets[r].c_str(), "min");
    for (const Runs& x : results[r]) std::printf("%8lld", (long long)x.front().stats.splits());
    std::printf("\n%-21s %-6s", "", "median");
    for (const Runs& x : results[r]) std::printf("%8lld", (long long)median(x).stats.splits());
    if (thesis) {
      std::printf("\n%-21s %-6s", "", "thesis");
      for (int t : thesisIndex) std::printf("%8.0f", (*thesis)[t]);
      std::printf("\n%-21s %-6s", "", "ratio");
      for (std::size_t c = 0; c < cases.size(); ++c)
        printRatio(double(median(results[r][c]).stats.splits()), (*thesis)[thesisIndex[c]]);
    }
    std::printf("\n");
  }

  std::printf(
      "\nSplit types, median seed (direct / indirect / sign conflict / fallback; "
      "forced vertices)\n");
  for (std::size_t r = 0; r < rulesets.size(); ++r) {
    double typed[3] = {0, 0, 0};
    long long fallback = 0, forced = 0, all = 0;
    std::printf("%-21s", rulesets[r].c_str());
    for (const Runs& x : results[r]) {
      const Stats& s = median(x).stats;
      std::printf(" %lld/%lld/%lld/%lld;%lld", (long long)s.splitsDirect,
                  (long long)s.splitsIndirect, (long long)s.splitsSignConflict,
                  (long long)s.splitsFallback, (long long)s.forcedVertices);
      typed[0] += double(s.splitsIndirect);
      typed[1] += double(s.splitsDirect);
      typed[2] += double(s.splitsSignConflict);
      fallback += s.splitsFallback;
      forced += s.forcedVertices;
      all += s.splits();
    }
    const double sum = typed[0] + typed[1] + typed[2];
    if (sum > 0)
      std::printf(
          "\n%-21s shares of all cases' typed splits: %.1f %% indirect, %.1f %% direct, "
          "%.1f %% sign conflict (thesis %.1f / %.1f / %.1f); fallback %lld of %lld splits, "
          "forced vertices %lld",
          "", 100 * typed[0] / sum, 100 * typed[1] / sum, 100 * typed[2] / sum,
          bench::kThesisIndirectPct, bench::kThesisDirectPct, bench::kThesisSignConflictPct,
          fallback, all, forced);
    std::printf("\n");
  }

  std::printf("\nMemory (table 6.6), median seed: ours, thesis, ours/thesis\n");
  for (std::size_t r = 0; r < rulesets.size(); ++r) {
    const bench::ThesisMemory* t = bench::thesisMemory(rulesets[r]);
    std::printf("%-21s %-14s", rulesets[r].c_str(), "");
    for (const auto& p : cases) std::printf("%8s", p.c.name.c_str());
    struct Metric {
      const char* name;
      double (*ours)(const Stats&);
      const bench::CaseRow* thesis;
    };
    const Metric metrics[] = {
        {"total MB", [](const Stats& s) { return s.memoryBytes / 1e6; }, t ? &t->totalMb : nullptr},
        {"% ptr grid", [](const Stats& s) { return s.pointerGridPercent; },
         t ? &t->pointerGridPct : nullptr},
        {"% embedded",
         [](const Stats& s) {
           return 100.0 * 8.0 * double(s.embeddedSamples) / double(s.memoryBytes);
         },
         t ? &t->embeddedPct : nullptr},
        {"ptr grid MB", [](const Stats& s) { return s.pointerGridBytes / 1e6; }, nullptr},
    };
    for (const Metric& m : metrics) {
      std::printf("\n  %-19s %-14s", m.name, "ours");
      for (const Runs& x : results[r]) std::printf("%8.2f", m.ours(median(x).stats));
      if (!m.thesis) continue;
      std::printf("\n  %-19s %-14s", "", "thesis");
      for (int c : thesisIndex) std::printf("%8.2f", (*m.thesis)[c]);
      std::printf("\n  %-19s %-14s", "", "ratio");
      for (std::size_t c = 0; c < cases.size(); ++c)
        printRatio(m.ours(median(results[r][c]).stats), (*m.thesis)[thesisIndex[c]]);
    }
    std::printf("\n");
  }

  std::printf("\nCPU seconds per run, median seed (thesis table 6.5's numbers are lost)\n");
  for (std::size_t r = 0; r < rulesets.size(); ++r) {
    std::printf("%-21s", rulesets[r].c_str());
    for (const Runs& x : results[r]) std::printf("%8.2f", median(x).cpuS);
    std::printf("\n");
  }
  return ok ? 0 : 1;
}

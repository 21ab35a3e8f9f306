#include "sim/mdh/split_rules.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "sim/mdh/rng.h"

namespace mdhd::mdh {

namespace {

// Distance (doubled, so it stays an integer) of a plane to the nearer cell side.
long long sideDistance2(const SplitCandidate& c, const GridBox& cell) {
  const int k = planeFor(c, cell);
  return 2LL * std::min(k - cell.lo[c.axis], cell.hi[c.axis] - k);
}

bool farEnough(const SplitCandidate& c, const SelectionContext& ctx) {
  return sideDistance2(c, ctx.cell) > 2.0 * ctx.toolRadius;
}

double score(Rule rule, const SplitCandidate& c, const SelectionContext& ctx) {
  switch (rule) {
    case Rule::kFFS:
      return static_cast<double>(sideDistance2(c, ctx.cell));
    case Rule::kFEFS:
      return farEnough(c, ctx) ? 1.0 : 0.0;
    case Rule::kCTD: {
      // The smaller the angle between the plane and t, the smaller |t . n|.
      const double len = std::sqrt(glm::dot(ctx.toolDirection, ctx.toolDirection));
      return len > 0 ? -std::abs(ctx.toolDirection[c.axis]) / len : 0.0;
    }
    case Rule::kSPT:
      if (c.type == SplitType::kDirect) return c.sole ? 1.0 : 0.0;
      return c.complete ? 2.0 : 0.0;
    case Rule::kFEFS_FFS:
    case Rule::kRS:
      break;
  }
  return 0.0;
}

void keepBest(std::vector<std::size_t>& ties, Rule rule,
              const std::vector<SplitCandidate>& candidates, const SelectionContext& ctx) {
  // NaN scores (a degenerate tool direction) rank lowest, so a tie set never empties.
  auto value = [&](std::size_t i) {
    const double x = score(rule, candidates[i], ctx);
    return std::isnan(x) ? -1e300 : x;
  };
  double best = -1e300;
  for (std::size_t i : ties) best = std::max(best, value(i));
  std::erase_if(ties, [&](std::size_t i) { return value(i) != best; });
}

}  // namespace

std::optional<Rule> ruleFromName(std::string_view name) {
  for (Rule r : {Rule::kFFS, Rule::kFEFS, Rule::kFEFS_FFS, Rule::kCTD, Rule::kSPT, Rule::kRS})
    if (ruleName(r) == name) return r;
  return std::nullopt;
}

std::string_view ruleName(Rule rule) {
  switch (rule) {
    case Rule::kFFS:
      return "FFS";
    case Rule::kFEFS:
      return "FEFS";
    case Rule::kFEFS_FFS:
      return "FEFS-FFS";
    case Rule::kCTD:
      return "CTD";
    case Rule::kSPT:
      return "SPT";
    case Rule::kRS:
      return "RS";
  }
  return "?";
}

int planeFor(const SplitCandidate& c, const GridBox& cell) {
  const int mid = (cell.lo[c.axis] + cell.hi[c.axis]) / 2;  // floor: ties go low
  return std::clamp(mid, c.lo, c.hi);
}

std::size_t chooseSplit(const std::vector<SplitCandidate>& candidates,
                        const std::vector<Rule>& rules, const SelectionContext& ctx) {
  std::vector<std::size_t> ties(candidates.size());
  for (std::size_t i = 0; i < ties.size(); ++i) ties[i] = i;
  for (Rule rule : rules) {
    if (ties.size() <= 1) break;
    if (rule == Rule::kRS) {
      return ties[splitMix64(ctx.randomKey) % ties.size()];
    }
    if (rule == Rule::kFEFS_FFS) {
      // FEFS when it splits the candidates into two classes, FFS otherwise.
      const bool mixed =
          std::any_of(ties.begin(), ties.end(),
                      [&](std::size_t i) { return farEnough(candidates[i], ctx); }) &&
          std::any_of(ties.begin(), ties.end(),
                      [&](std::size_t i) { return !farEnough(candidates[i], ctx); });
      keepBest(ties, mixed ? Rule::kFEFS : Rule::kFFS, candidates, ctx);
      continue;
    }
    keepBest(ties, rule, candidates, ctx);
  }
  return ties.front();
}

}  // namespace mdhd::mdh

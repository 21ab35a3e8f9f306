#pragma once
// Selection among split intervals (thesis 3.3): rules in priority order, each
// keeping only the best-scoring candidates, the next rule breaking ties.
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/mdh/grid.h"
#include "sim/mdh/split_candidate.h"

namespace mdhd::mdh {

enum class Rule : std::uint8_t { kFFS, kFEFS, kFEFS_FFS, kCTD, kSPT, kRS };

std::optional<Rule> ruleFromName(std::string_view name);  // "FFS", "FEFS-FFS", ...
std::string_view ruleName(Rule rule);

struct SelectionContext {
  GridBox cell;
  glm::dvec3 toolDirection{0.0, 0.0, 1.0};
  double toolRadius = 0.0;  // grid units, FEFS's threshold
  std::uint64_t randomKey = 0;
};

// The plane of a split interval closest to the middle of the cell.
int planeFor(const SplitCandidate& c, const GridBox& cell);

// Index of the chosen candidate (candidates must not be empty).
std::size_t chooseSplit(const std::vector<SplitCandidate>& candidates,
                        const std::vector<Rule>& rules, const SelectionContext& ctx);

}  // namespace mdhd::mdh

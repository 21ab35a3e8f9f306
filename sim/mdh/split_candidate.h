#pragma once
// A split interval (thesis 3.3): a range of grid planes along one axis, any of
// which would do the same job, with the kind of split it came from.
#include <cstdint>

namespace mdhd::mdh {

enum class SplitType : std::uint8_t { kDirect, kIndirect, kSignConflict, kFallback };
inline constexpr int kSplitTypes = 4;

struct SplitCandidate {
  int axis = 0;
  int lo = 0;  // first plane (absolute grid index), strictly inside the cell
  int hi = 0;  // last plane
  SplitType type = SplitType::kFallback;
  bool complete = false;  // isolates fully (sign conflict / indirect)
  bool sole = false;      // the only member of its DSP series (direct)
};

}  // namespace mdhd::mdh

#pragma once
// Consecutive cutting steps that translate one cutter along a chain of poses, cut
// as one: the union of their sweeps goes to the stock once (Stock::cutIfFast), so
// the walls a raster's steps move a grid spacing at a time are rewritten once per
// batch instead of once per step. The stock comes out as the steps one by one would
// leave it (cutIfFast), up to a crossing the union may place elsewhere inside its
// grid edge; a batch that needs the slow path (a new direction or a split, whose
// choice depends on the order of the steps) is cut again step by step, and the batch
// size backs off for a while.
//
// With a chain tolerance t > 0, the batch's union is cut along the chain less the
// points between two straight feed steps that a chord can skip within t
// (geom::simplifyPolyline): the swept volume then stays within t of the steps' (the
// same shape translated along paths within t of each other), and a raster of short
// moves along a smooth surface is cut with a few long translations instead of many
// short ones. Arc steps (already chords within the job's tolerance), rapids and
// turns keep every point.
//
// Until a batch is flushed the stock still holds what it will remove: a probe of
// it then overstates contacts, never misses one (flush, then probe again).
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/geometry/fresh_region.h"
#include "sim/geometry/swept_volume.h"
#include "sim/geometry/tool_part.h"
#include "sim/geometry/tool_pose.h"
#include "sim/mdh/stock.h"

namespace mdhd::check {

struct CutBatchStats {
  std::int64_t batches = 0;  // cuts of two steps or more the fast path took
  std::int64_t steps = 0;    // steps cut in them
  std::int64_t refused = 0;  // batches cut again step by step
};

class CutBatch {
 public:
  // At most `max_steps` steps per cut (1: every step cut on its own); chain points
  // dropped within `chain_tolerance` mm (0: none).
  explicit CutBatch(int max_steps, double chain_tolerance = 0.0);

  bool empty() const { return lines_.empty(); }

  // Adds the step of `part` from `a` to `b` (same axis) with its sweep and fresh
  // region (geom::freshRegion: the chain's previous step ended at `a`). With `ask`,
  // returns whether it removes material: whether `sweep` reaches into the stock less
  // the pending sweeps along some z grid line (Stock::removesMaterial), what the step
  // cut on its own would find; without, false (its motion is known to cut already).
  // `straight`: a step of a straight feed move (its ends may be dropped from the
  // chain where the neighbouring step is one too).
  // The caller flushes first unless the step continues the pending chain (same part,
  // starting at its last pose).
  bool add(const mdh::Stock& stock, const geom::ToolPart& part, const geom::ToolPose& a,
           const geom::ToolPose& b, geom::SweptVolume sweep, geom::FreshRegion fresh,
           const glm::dvec3& direction, int line, bool straight, bool ask = true);
  bool full() const { return static_cast<int>(lines_.size()) >= cap_; }

  // Cuts the pending steps; `cut(line, result)` hears of every cut made: one for a
  // batch (its first step's line; the fast path raises no overhang events), one per
  // step when it was cut step by step.
  void flush(mdh::Stock& stock, const std::function<void(int, const mdh::CutResult&)>& cut);

  const CutBatchStats& stats() const { return stats_; }

 private:
  int max_ = 1;
  int cap_ = 1;  // the current limit: max_, lowered after a refusal
  double chainTolerance_ = 0.0;
  const geom::ToolPart* part_ = nullptr;
  glm::dvec3 direction_{0.0, 0.0, 1.0};
  std::vector<geom::ToolPose> poses_;  // the chain: start, then each step's end
  std::vector<geom::SweptVolume> sweeps_;
  std::vector<geom::FreshRegion> fresh_;
  std::vector<int> lines_;
  std::vector<std::uint8_t> straight_;
  glm::dvec3 lastHit_{0.0};  // where the last step asked removed, from its end tip
  CutBatchStats stats_;
};

}  // namespace mdhd::check

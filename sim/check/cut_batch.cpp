#include "sim/check/cut_batch.h"

#include <algorithm>

namespace mdhd::check {

CutBatch::CutBatch(int max_steps) : max_(std::max(1, max_steps)), cap_(max_) {}

bool CutBatch::add(const mdh::Stock& stock, const geom::ToolPart& part, const geom::ToolPose& a,
                   const geom::ToolPose& b, geom::SweptVolume sweep, geom::FreshRegion fresh,
                   const glm::dvec3& direction, int line, bool ask) {
  bool removes = false;
  if (ask) {
    std::vector<const geom::LineSolid*> pending;
    pending.reserve(sweeps_.size());
    for (const geom::SweptVolume& s : sweeps_) pending.push_back(&s);
    // Steps along a raster remove at the same place relative to the tool: start there.
    glm::dvec3 hit;
    removes = stock.removesMaterial(sweep, &fresh, pending, b.tip + lastHit_, &hit);
    if (removes) lastHit_ = hit - b.tip;
  }
  if (empty()) {
    part_ = &part;
    direction_ = direction;
    poses_.assign(1, a);
  }
  poses_.push_back(b);
  sweeps_.push_back(std::move(sweep));
  fresh_.push_back(std::move(fresh));
  lines_.push_back(line);
  return removes;
}

void CutBatch::flush(mdh::Stock& stock,
                     const std::function<void(int, const mdh::CutResult&)>& cut) {
  if (empty()) return;
  const auto steps = static_cast<std::uint64_t>(lines_.size());
  bool taken = false;
  if (steps == 1) {
    cut(lines_[0], stock.cut(sweeps_[0], direction_, &fresh_[0]));
    taken = true;
  } else {
    geom::FreshRegion region;
    for (const geom::FreshRegion& f : fresh_)
      region.pieces.insert(region.pieces.end(), f.pieces.begin(), f.pieces.end());
    const geom::SweptVolume chain = geom::SweptVolume::chainOfTranslations(*part_, poses_);
    if (const auto r = stock.cutIfFast(chain, direction_, &region, steps)) {
      cut(lines_[0], *r);
      ++stats_.batches;
      stats_.steps += static_cast<std::int64_t>(steps);
      taken = true;
    } else {
      ++stats_.refused;
      for (std::size_t i = 0; i < lines_.size(); ++i)
        cut(lines_[i], stock.cut(sweeps_[i], direction_, &fresh_[i]));
    }
  }
  // Where one batch needed the slow path the next ones likely do too (a region of
  // overhangs): fall back to single steps there and grow again once they pass.
  if (!taken)
    cap_ = 1;
  else if (static_cast<int>(steps) >= cap_)
    cap_ = std::min(max_, 2 * cap_);
  poses_.clear();
  sweeps_.clear();
  fresh_.clear();
  lines_.clear();
}

}  // namespace mdhd::check

#include "sim/check/cut_batch.h"

#include <algorithm>
#include <memory>

#include "sim/geometry/polyline_simplify.h"

namespace mdhd::check {

CutBatch::CutBatch(int max_steps, double chain_tolerance)
    : max_(std::max(1, max_steps)), cap_(max_), chainTolerance_(std::max(0.0, chain_tolerance)) {}

namespace {

// The chain's poses less those a chord skips within `tolerance`: a pose
// between two straight steps may go, the first, the last and any other stay.
std::vector<geom::ToolPose> simplifiedChain(const std::vector<geom::ToolPose>& poses,
                                            const std::vector<std::uint8_t>& straight,
                                            double tolerance) {
  if (!(tolerance > 0.0) || poses.size() <= 2) return poses;
  std::vector<glm::dvec3> tips;
  std::vector<std::uint8_t> fixed(poses.size(), 1);
  tips.reserve(poses.size());
  for (const geom::ToolPose& p : poses) tips.push_back(p.tip);
  for (std::size_t k = 1; k + 1 < poses.size(); ++k)
    fixed[k] = !(straight[k - 1] != 0 && straight[k] != 0);
  std::vector<std::size_t> kept;
  geom::simplifyPolyline(tips, fixed, tolerance, kept);
  std::vector<geom::ToolPose> out;
  out.reserve(kept.size());
  for (std::size_t k : kept) out.push_back(poses[k]);
  return out;
}

}  // namespace

bool CutBatch::add(const mdh::Stock& stock, const geom::ToolPart& part, const geom::ToolPose& a,
                   const geom::ToolPose& b, geom::SweptVolume sweep, geom::FreshRegion fresh,
                   const glm::dvec3& direction, int line, bool straight, bool ask) {
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
  straight_.push_back(straight ? 1 : 0);
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
    // Shared: the stock's cells may keep it for crossings they compute later.
    auto chain = std::make_shared<const geom::SweptVolume>(geom::SweptVolume::chainOfTranslations(
        *part_, simplifiedChain(poses_, straight_, chainTolerance_)));
    if (const auto r = stock.cutIfFast(std::shared_ptr<const geom::LineSolid>(std::move(chain)),
                                       direction_, &region, steps)) {
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
  straight_.clear();
}

}  // namespace mdhd::check

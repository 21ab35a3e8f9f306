#include "sim/mdh/shared_samples.h"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>

namespace mdhd::mdh {

bool leafSolidAt(const LeafView& leaf, const GridPoint& p) {
  if (leaf.state != CellState::kPartial || leaf.map == nullptr)
    return leaf.state == CellState::kSolid;
  const ThreeMap& m = *leaf.map;
  const GridBox& b = m.box();
  return m.columnSolidAt(p[m.uAxis()] - b.lo[m.uAxis()], p[m.vAxis()] - b.lo[m.vAxis()],
                         p[m.axis()]);
}

namespace {

// A leaf's crossings with each row's packed offsets computed once: a walk from the
// row's start for every lookup made checking a large cell's faces quadratic.
class LeafCrossings {
 public:
  explicit LeafCrossings(const LeafView& leaf) : leaf_(leaf) {}
  double at(const GridPoint& p, int axis, bool* sampled);

 private:
  const LeafView& leaf_;
  std::vector<std::vector<std::size_t>> offsets_[2];  // per family and row, per edge
};

double LeafCrossings::at(const GridPoint& p, int axis, bool* sampled) {
  const double none = std::nan("");
  if (sampled) *sampled = true;
  if (leaf_.state != CellState::kPartial || leaf_.map == nullptr) return none;
  const ThreeMap& m = *leaf_.map;
  // A plain heightmap's parent heights may come from interpolated crossings
  // (a resample), so none of its crossings is a sample another cell shares.
  if (sampled) *sampled = m.threeWay();
  const GridBox& b = m.box();
  const int a = m.axis(), u = m.uAxis(), v = m.vAxis();
  if (axis == a) {
    const int iu = p[u] - b.lo[u], iv = p[v] - b.lo[v];
    return m.columnSolidAt(iu, iv, p[a]) != m.columnSolidAt(iu, iv, p[a] + 1) ? m.height(iu, iv)
                                                                              : none;
  }
  const int family = axis == u ? 0 : 1;
  const int r = family == 0 ? p[v] - b.lo[v] : p[u] - b.lo[u];
  const int edge = p[axis] - b.lo[axis];
  const ColumnStraddle st = m.straddleEdge(family, r, edge);
  const int at = st.indexOf(p[a]);
  if (at < 0) return none;
  if (!m.threeWay())
    return m.interpolatedCrossing(m.rowHeight(family, r, edge), m.rowHeight(family, r, edge + 1),
                                  p[axis], p[a]);
  auto& rows = offsets_[family];
  if (rows.empty()) rows.resize(static_cast<std::size_t>(m.rowCount(family)));
  std::vector<std::size_t>& offsets = rows[static_cast<std::size_t>(r)];
  if (offsets.empty()) {
    offsets.resize(static_cast<std::size_t>(m.edgesInRow(family)) + 1, 0);
    for (int e = 0; e < m.edgesInRow(family); ++e)
      offsets[e + 1] = offsets[e] + static_cast<std::size_t>(m.straddleEdge(family, r, e).total());
  }
  return m.row(family, r)[offsets[edge] + static_cast<std::size_t>(at)];
}

}  // namespace

double leafCrossingAt(const LeafView& leaf, const GridPoint& p, int axis, bool* sampled) {
  return LeafCrossings(leaf).at(p, axis, sampled);
}

std::string SampleDisagreement::describe() const {
  auto box = [](const GridBox& g) {
    std::ostringstream s;
    s << "[" << g.lo[0] << "," << g.lo[1] << "," << g.lo[2] << "]-[" << g.hi[0] << "," << g.hi[1]
      << "," << g.hi[2] << "]";
    return s.str();
  };
  std::ostringstream s;
  s.precision(17);
  if (axis < 0)
    s << "vertex";
  else
    s << "edge along "
      << "xyz"[axis] << " from";
  s << " (" << vertex[0] << "," << vertex[1] << "," << vertex[2] << "): leaf " << box(first)
    << " says " << firstValue << ", leaf " << box(second) << " says " << secondValue;
  return s.str();
}

namespace {

struct Said {
  GridBox box;
  double value;
  bool sampled;
};

bool same(double x, double y) {
  return (std::isnan(x) && std::isnan(y)) || x == y;
}

}  // namespace

std::vector<SampleDisagreement> sharedSampleDisagreements(const Stock& stock, std::size_t limit) {
  const GridBox all = stock.grid().all();
  const std::uint64_t nx = all.hi[0] + 1, ny = all.hi[1] + 1;
  auto key = [&](const GridPoint& p, int slot) {
    return ((p[0] + nx * (p[1] + ny * std::uint64_t(p[2]))) << 2) | std::uint64_t(slot);
  };
  std::unordered_map<std::uint64_t, Said> seen;
  std::vector<SampleDisagreement> out;
  auto record = [&](const LeafView& leaf, const GridPoint& p, int axis, double value,
                    bool sampled) {
    const auto [it, fresh] =
        seen.try_emplace(key(p, axis < 0 ? 3 : axis), Said{leaf.box, value, sampled});
    if (fresh || it->second.box == leaf.box || out.size() >= limit) return;
    const Said& s = it->second;
    // Interpolated crossings (plain heightmaps) need only agree on being there.
    const bool agree =
        (sampled && s.sampled) ? same(s.value, value) : std::isnan(s.value) == std::isnan(value);
    if (!agree) out.push_back({p, axis, s.box, leaf.box, s.value, value});
  };
  stock.forEachLeaf([&](const LeafView& leaf) {
    const GridBox& b = leaf.box;
    LeafCrossings crossings(leaf);
    for (int f = 0; f < 3; ++f) {
      const int u = axisU(f), v = axisV(f);
      for (int side : {b.lo[f], b.hi[f]}) {
        GridPoint p{};
        p[f] = side;
        for (p[v] = b.lo[v]; p[v] <= b.hi[v]; ++p[v])
          for (p[u] = b.lo[u]; p[u] <= b.hi[u]; ++p[u]) {
            record(leaf, p, -1, leafSolidAt(leaf, p) ? 1.0 : 0.0, true);
            for (int e : {u, v}) {
              if (p[e] == b.hi[e]) continue;
              bool sampled = true;
              const double c = crossings.at(p, e, &sampled);
              record(leaf, p, e, c, sampled);
            }
          }
        if (b.lo[f] == b.hi[f]) break;
      }
    }
  });
  return out;
}

}  // namespace mdhd::mdh

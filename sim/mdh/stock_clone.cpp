// Deep copy of a stock: the kD-tree is owned through unique_ptrs, so it is copied
// node by node.
#include "sim/mdh/stock.h"

namespace mdhd::mdh {

void copyCell(const Cell& from, Cell& to) {
  to.box = from.box;
  to.state = from.state;
  to.id = from.id;
  to.volume = from.volume;
  to.splitAxis = from.splitAxis;
  to.splitAt = from.splitAt;
  if (from.map) to.map = std::make_unique<ThreeMap>(*from.map);
  // The solids are shared: they never change.
  to.pending = from.pending ? std::make_unique<PendingCuts>(*from.pending) : nullptr;
  for (int i = 0; i < 2; ++i) {
    if (!from.child[i]) continue;
    to.child[i] = std::make_unique<Cell>();
    copyCell(*from.child[i], *to.child[i]);
  }
}

Stock::Stock(const Stock& other, CloneTag)
    : options_(other.options_),
      grid_(other.grid_),
      bricks_(other.bricks_),
      roots_(other.roots_.size()),
      totals_(other.totals_),
      step_(other.step_),
      toolRadius_(other.toolRadius_),
      threads_(other.threads_),
      pending_(other.pending_.load(std::memory_order_acquire)) {
  for (int a = 0; a < 3; ++a) brickSize_[a] = other.brickSize_[a];
  for (std::size_t i = 0; i < roots_.size(); ++i) copyCell(other.roots_[i], roots_[i]);
}

std::unique_ptr<Stock> Stock::clone() const {
  return std::unique_ptr<Stock>(new Stock(*this, CloneTag{}));
}

}  // namespace mdhd::mdh

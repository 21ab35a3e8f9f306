// The live shadow's mesh, built in memory: a whole binary STL within the cap, and
// nothing (with the reason) over it, so a fine live stock cannot take the service's
// memory with it.
#include <cstdint>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "daemon/stock_stl.h"
#include "sim/geometry/line_solid.h"
#include "sim/mdh/stock.h"

namespace mdhd::cli {
namespace {

std::uint32_t triangleCount(const std::string& stl) {
  std::uint32_t n = 0;
  std::memcpy(&n, stl.data() + 80, 4);
  return n;
}

TEST(StockStlBytes, AWholeFileWithinTheCapAndNothingOverIt) {
  mdh::StockOptions options;
  options.density = 4;
  options.threads = 1;
  const mdh::Stock stock(geom::Aabb{{0, 0, 0}, {10, 8, 5}}, options);

  std::string stl;
  const StlOutcome whole = stockStlBytes(stock, "test", StlLimits{}, stl);
  ASSERT_EQ(whole.failure, StlOutcome::Failure::kNone) << whole.error;
  ASSERT_GE(stl.size(), 84u);
  const std::uint32_t n = triangleCount(stl);
  EXPECT_GE(n, 12u);  // a box: at least two triangles a face
  EXPECT_EQ(stl.size(), 84u + 50u * n);

  StlLimits capped;
  capped.max_bytes = stl.size() - 1;
  std::string over = "stale";
  const StlOutcome refused = stockStlBytes(stock, "test", capped, over);
  EXPECT_EQ(refused.failure, StlOutcome::Failure::kTooLarge);
  EXPECT_NE(refused.error.find("larger than the limit of " + std::to_string(stl.size() - 1)),
            std::string::npos)
      << refused.error;
  EXPECT_TRUE(over.empty());

  capped.max_bytes = stl.size();
  std::string exact;
  EXPECT_EQ(stockStlBytes(stock, "test", capped, exact).failure, StlOutcome::Failure::kNone);
  EXPECT_EQ(exact, stl);
}

}  // namespace
}  // namespace mdhd::cli

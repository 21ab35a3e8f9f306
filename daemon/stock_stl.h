#pragma once
// The final stock as a binary STL file, written whole or not at all: into a
// temporary beside the target, flushed to disk, then renamed over it (a symbolic
// link's target: the link stays). A target that exists and is no regular file (a
// pipe, a terminal, /dev/stdout, /dev/null) is written straight through instead,
// the triangle count first (the mesh is made twice); renaming over it replaced it
// by a file. `mdhd check --mesh` and the service write the same bytes for the same
// job, on any number of meshing threads.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>

#include "sim/mdh/stock.h"

namespace mdhd::cli {

// "" on success, else what went wrong (nothing is left under `path` then).
std::string writeStockStl(const mdh::Stock& stock, const std::filesystem::path& path,
                          int threads = 1);

// What the service bounds a mesh by. The flag and the size are looked at every
// 1024 triangles, so a cancel stops meshing and writing within milliseconds and a
// mesh over the cap is abandoned at the cap, not after filling the disk.
struct StlLimits {
  const std::atomic<bool>* cancel = nullptr;  // raised: check::Cancelled is thrown
  std::uint64_t max_bytes = 0;                // 0: none
};

struct StlOutcome {
  enum class Failure { kNone, kTooLarge, kWrite };
  Failure failure = Failure::kNone;
  std::string error;  // "" on success
};

// The stock as binary STL bytes in `out` (a live shadow's mesh, served from memory),
// within `limits`: over `max_bytes` it stops at the cap and says so, `out` cleared.
StlOutcome stockStlBytes(const mdh::Stock& stock, const std::string& header,
                         const StlLimits& limits, std::string& out);

// As above, within `limits`. A cancelled or failed write leaves nothing under
// `path` (nor its temporary); check::Cancelled is rethrown after that.
StlOutcome writeStockStl(const mdh::Stock& stock, const std::filesystem::path& path, int threads,
                         const StlLimits& limits);

}  // namespace mdhd::cli

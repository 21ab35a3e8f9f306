#pragma once
// The final stock as a binary STL file, written whole or not at all: into a
// temporary beside the target, flushed to disk, then renamed over it. `mdhd check
// --mesh` and the service write the same bytes for the same job, on any number of
// meshing threads.
#include <filesystem>
#include <string>

#include "sim/mdh/stock.h"

namespace mdhd::cli {

// "" on success, else what went wrong (nothing is left under `path` then).
std::string writeStockStl(const mdh::Stock& stock, const std::filesystem::path& path,
                          int threads = 1);

}  // namespace mdhd::cli

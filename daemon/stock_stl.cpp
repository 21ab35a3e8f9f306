#include "daemon/stock_stl.h"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>

#include "protocol/stl.h"
#include "sim/mesh/mesher.h"

namespace mdhd::cli {
namespace {

// fsync of a file or folder by path: the data (or the rename) reaches the disk.
void syncPath(const std::filesystem::path& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  fsync(fd);
  close(fd);
}

}  // namespace

std::string writeStockStl(const mdh::Stock& stock, const std::filesystem::path& path, int threads) {
  std::filesystem::path partial = path;
  partial += ".partial";
  try {
    {
      std::ofstream file(partial, std::ios::binary | std::ios::trunc);
      if (!file) return "cannot write " + partial.string();
      protocol::StlWriter stl(file, "mdhd check: final stock (mm, workpiece frame)");
      mesh::MeshOptions options;
      options.threads = threads;
      mesh::meshStock(stock, stl, options);
      stl.finish();
    }
    syncPath(partial);
    std::filesystem::rename(partial, path);
    syncPath(path.has_parent_path() ? path.parent_path() : std::filesystem::path("."));
    return "";
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    return "cannot write " + path.string() + ": " + e.what();
  }
}

}  // namespace mdhd::cli

#include "daemon/stock_stl.h"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>

#include "protocol/stl.h"
#include "sim/check/simulation.h"
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

struct MeshTooLarge : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Between the mesher and the STL writer: every 1024 triangles, the cancel flag, the
// size cap and the file's state (a full disk shows there long before finish()).
class GuardedSink final : public mesh::MeshSink {
 public:
  GuardedSink(mesh::MeshSink& out, const std::ostream& file, const StlLimits& limits)
      : out_(out), file_(file), limits_(limits) {}
  void triangle(const mesh::MeshVertex& a, const mesh::MeshVertex& b, const mesh::MeshVertex& c,
                bool exterior) override {
    if ((++count_ & 1023u) == 0) check();
    out_.triangle(a, b, c, exterior);
  }
  void check() const {
    if (limits_.cancel != nullptr && limits_.cancel->load(std::memory_order_relaxed))
      throw check::Cancelled();
    const std::uint64_t bytes =
        protocol::kStlHeaderBytes + 4 + count_ * protocol::kStlTriangleBytes;
    if (limits_.max_bytes > 0 && bytes > limits_.max_bytes) {
      throw MeshTooLarge("the mesh is larger than the limit of " +
                         std::to_string(limits_.max_bytes) + " bytes");
    }
    if (!file_) throw std::runtime_error("the file could not be written (disk full?)");
  }

 private:
  mesh::MeshSink& out_;
  const std::ostream& file_;
  const StlLimits& limits_;
  std::uint64_t count_ = 0;
};

}  // namespace

StlOutcome writeStockStl(const mdh::Stock& stock, const std::filesystem::path& path, int threads,
                         const StlLimits& limits) {
  std::filesystem::path partial = path;
  partial += ".partial";
  auto dropPartial = [&] {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
  };
  try {
    {
      std::ofstream file(partial, std::ios::binary | std::ios::trunc);
      if (!file) return {StlOutcome::Failure::kWrite, "cannot write " + partial.string()};
      protocol::StlWriter stl(file, "mdhd check: final stock (mm, workpiece frame)");
      GuardedSink sink(stl, file, limits);
      mesh::MeshOptions options;
      options.threads = threads;
      mesh::meshStock(stock, sink, options);
      sink.check();
      stl.finish();
    }
    syncPath(partial);
    std::filesystem::rename(partial, path);
    syncPath(path.has_parent_path() ? path.parent_path() : std::filesystem::path("."));
    return {};
  } catch (const check::Cancelled&) {
    dropPartial();
    throw;
  } catch (const MeshTooLarge& e) {
    dropPartial();
    return {StlOutcome::Failure::kTooLarge, e.what()};
  } catch (const std::exception& e) {
    dropPartial();
    return {StlOutcome::Failure::kWrite, "cannot write " + path.string() + ": " + e.what()};
  }
}

std::string writeStockStl(const mdh::Stock& stock, const std::filesystem::path& path, int threads) {
  return writeStockStl(stock, path, threads, StlLimits{}).error;
}

}  // namespace mdhd::cli

#include "daemon/stock_stl.h"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <limits>
#include <sstream>
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

class CountingSink final : public mesh::MeshSink {
 public:
  void triangle(const mesh::MeshVertex&, const mesh::MeshVertex&, const mesh::MeshVertex&,
                bool) override {
    ++count;
  }
  std::uint64_t count = 0;
};

const char* const kHeader = "mdhd check: final stock (mm, workpiece frame)";

}  // namespace

StlOutcome stockStlBytes(const mdh::Stock& stock, const std::string& header,
                         const StlLimits& limits, std::string& out) {
  out.clear();
  std::ostringstream text;
  try {
    protocol::StlWriter stl(text, header);
    GuardedSink sink(stl, text, limits);
    mesh::meshStock(stock, sink);
    sink.check();
    stl.finish();
  } catch (const MeshTooLarge& e) {
    return {StlOutcome::Failure::kTooLarge, e.what()};
  }
  out = std::move(text).str();
  return {};
}

namespace {

// A pipe, terminal or device (`--mesh /dev/stdout`, a FIFO): written straight
// through, the triangle count first, so the mesh is made twice (once to count).
StlOutcome writeThrough(const mdh::Stock& stock, const std::filesystem::path& path, int threads,
                        const StlLimits& limits) {
  mesh::MeshOptions options;
  options.threads = threads;
  std::ofstream file(path, std::ios::binary);
  if (!file) return {StlOutcome::Failure::kWrite, "cannot write " + path.string()};
  try {
    CountingSink counter;
    GuardedSink countSink(counter, file, limits);
    mesh::meshStock(stock, countSink, options);
    countSink.check();
    if (counter.count > std::numeric_limits<std::uint32_t>::max())
      throw std::runtime_error(std::to_string(counter.count) +
                               " triangles do not fit the format's 32-bit count");
    protocol::StlWriter stl(file, kHeader, static_cast<std::uint32_t>(counter.count));
    GuardedSink sink(stl, file, limits);
    mesh::meshStock(stock, sink, options);
    sink.check();
    stl.finish();
    return {};
  } catch (const MeshTooLarge& e) {
    return {StlOutcome::Failure::kTooLarge, e.what()};
  } catch (const check::Cancelled&) {
    throw;
  } catch (const std::exception& e) {
    return {StlOutcome::Failure::kWrite, "cannot write " + path.string() + ": " + e.what()};
  }
}

}  // namespace

StlOutcome writeStockStl(const mdh::Stock& stock, const std::filesystem::path& asked, int threads,
                         const StlLimits& limits) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(asked, ec);  // of what a link names
  if (fs::is_directory(status))
    return {StlOutcome::Failure::kWrite, "cannot write " + asked.string() + ": it is a folder"};
  // Only a regular file (or a new one) is replaced by renaming a finished temporary
  // over it: renaming over /dev/stdout or a FIFO replaced the device or pipe by a file.
  if (fs::exists(status) && !fs::is_regular_file(status))
    return writeThrough(stock, asked, threads, limits);
  // A symbolic link is followed: the file it names is replaced, the link stays.
  fs::path path = asked;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(path, ec)); ++hops) {
    const fs::path to = fs::read_symlink(path, ec);
    if (ec || hops == 40) return writeThrough(stock, asked, threads, limits);
    path = to.is_absolute() ? to : path.parent_path() / to;
    // /dev/stdout on a file: /proc/self/fd/1 names the open file, not a path to
    // replace (the shell's descriptor would keep the old, empty one).
    if (path.string().starts_with("/proc/")) return writeThrough(stock, asked, threads, limits);
  }
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
      protocol::StlWriter stl(file, kHeader);
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

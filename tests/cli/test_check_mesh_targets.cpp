// mdhd check --mesh into what is not a plain new file: a symbolic link (its target
// gets the mesh, the link stays), a FIFO (a reader gets the whole STL, the FIFO stays
// one) and a folder (refused).
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "daemon/cli.h"
#include "tests/cli/example_path.h"

namespace mdhd::cli {
namespace {

namespace fs = std::filesystem;

class MeshTarget : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mdhd_mesh_target_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::copy_file(test_support::example("machine-3axis.json"), dir_ / "machine.json");
    std::ofstream(dir_ / "p.ngc")
        << "G21 G90 G17\nT1 M6\nG43 H1\nM3 S10000\nG0 X5 Y5 Z5\nG1 Z-2 F300\nG1 X15 F600\n"
           "G0 Z5\nM5\nM30\n";
    std::ofstream(dir_ / "job.json") << R"({
      "machine_file": "machine.json",
      "tools": [{"number": 1, "shape": "flat", "diameter": 4, "flute_length": 10, "length": 40}],
      "stock": {"box": {"min": [0, 0, -10], "max": [20, 20, 0]}},
      "program_file": "p.ngc",
      "options": {"density": 4}})";
  }
  void TearDown() override { fs::remove_all(dir_); }

  int check(const fs::path& mesh) {
    std::ostringstream out, err;
    const int status = runCheck({(dir_ / "job.json").string(), "--report",
                                 (dir_ / "r.json").string(), "--mesh", mesh.string()},
                                out, err);
    err_ = err.str();
    return status;
  }
  // The triangle count the file's header promises, or -1 when its size disagrees.
  static std::int64_t stlTriangles(const std::string& bytes) {
    if (bytes.size() < 84) return -1;
    std::uint32_t n;
    std::memcpy(&n, bytes.data() + 80, 4);
    return bytes.size() == 84 + 50 * std::size_t(n) ? std::int64_t(n) : -1;
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
  }

  fs::path dir_;
  std::string err_;
};

TEST_F(MeshTarget, ASymbolicLinkKeepsPointingAtTheMesh) {
  std::ofstream(dir_ / "real.stl") << "old";
  fs::create_symlink("real.stl", dir_ / "link.stl");
  ASSERT_EQ(check(dir_ / "link.stl"), 0) << err_;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "link.stl")));
  EXPECT_GT(stlTriangles(slurp(dir_ / "real.stl")), 100);
  EXPECT_FALSE(fs::exists(dir_ / "real.stl.partial"));
  EXPECT_FALSE(fs::exists(dir_ / "link.stl.partial"));
  // A dangling link: the file it names is made.
  fs::remove(dir_ / "real.stl");
  ASSERT_EQ(check(dir_ / "link.stl"), 0) << err_;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "link.stl")));
  EXPECT_GT(stlTriangles(slurp(dir_ / "real.stl")), 100);
}

TEST_F(MeshTarget, AFifoGetsTheWholeMesh) {
  const fs::path fifo = dir_ / "mesh.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // The read end is opened first and never blocks, so the check's open does not wait
  // and a check that never writes into the FIFO cannot hang the test.
  const int fd = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  auto status = std::async(std::launch::async, [&] { return check(fifo); });
  std::string got;
  char buffer[65536];
  for (bool done = false;;) {
    pollfd p{fd, POLLIN, 0};
    poll(&p, 1, 20);
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) {
      got.append(buffer, static_cast<std::size_t>(n));
      continue;
    }
    if (done) break;  // drained after the check ended
    done = status.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  }
  close(fd);
  EXPECT_EQ(status.get(), 0) << err_;
  EXPECT_GT(stlTriangles(got), 100) << got.size() << " bytes";
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
  EXPECT_FALSE(fs::exists(dir_ / "mesh.fifo.partial"));
  // The same bytes as a plain file gets.
  ASSERT_EQ(check(dir_ / "plain.stl"), 0) << err_;
  EXPECT_TRUE(got == slurp(dir_ / "plain.stl"));
}

TEST_F(MeshTarget, AFolderIsRefused) {
  fs::create_directories(dir_ / "out");
  EXPECT_EQ(check(dir_ / "out"), 2);
  EXPECT_NE(err_.find("folder"), std::string::npos) << err_;
  EXPECT_TRUE(fs::is_directory(dir_ / "out"));
  EXPECT_TRUE(fs::is_empty(dir_ / "out"));
}

}  // namespace
}  // namespace mdhd::cli

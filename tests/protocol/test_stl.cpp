// Binary STL writer: exact bytes of header, count and records; the count
// patched on seekable streams, promised up front on others.
#include "protocol/stl.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <streambuf>
#include <string>

#include <gtest/gtest.h>

namespace mdhd::protocol {
namespace {

std::uint32_t u32At(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t(static_cast<unsigned char>(s[at + i])) << (8 * i);
  return v;
}

float f32At(const std::string& s, std::size_t at) {
  const std::uint32_t bits = u32At(s, at);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// An output that cannot seek, like a pipe.
class PipeBuf final : public std::streambuf {
 public:
  std::string data;

 protected:
  int_type overflow(int_type c) override {
    if (c != traits_type::eof()) data.push_back(static_cast<char>(c));
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    data.append(s, static_cast<std::size_t>(n));
    return n;
  }
};

TEST(Stl, WritesHeaderCountAndRecordsLittleEndian) {
  std::stringstream out;
  StlWriter w(out, "unit square");
  w.add({0, 0, 0}, {1, 0, 0}, {1, 1, 0});
  w.add({0, 0, 0}, {1, 1, 0}, {0, 1, 0.5});
  w.finish();
  const std::string s = out.str();
  ASSERT_EQ(s.size(), kStlHeaderBytes + 4 + 2 * kStlTriangleBytes);
  EXPECT_EQ(s.substr(0, 11), "unit square");
  EXPECT_EQ(s[11], '\0');
  EXPECT_EQ(s[79], '\0');
  EXPECT_EQ(u32At(s, 80), 2u);
  // First record: normal +z, then the vertices as given.
  EXPECT_EQ(f32At(s, 84), 0.0f);
  EXPECT_EQ(f32At(s, 88), 0.0f);
  EXPECT_EQ(f32At(s, 92), 1.0f);
  const float v[9] = {0, 0, 0, 1, 0, 0, 1, 1, 0};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(f32At(s, 96 + 4 * i), v[i]) << i;
  EXPECT_EQ(s[132], '\0');
  EXPECT_EQ(s[133], '\0');
  // Second record's normal is the unit right-hand normal: (1,1,0) x (0,1,0.5) = (0.5,-0.5,1).
  const std::size_t r = 84 + 50;
  const double len = std::sqrt(1.5);
  EXPECT_NEAR(f32At(s, r), 0.5 / len, 1e-7);
  EXPECT_NEAR(f32At(s, r + 4), -0.5 / len, 1e-7);
  EXPECT_NEAR(f32At(s, r + 8), 1.0 / len, 1e-7);
  EXPECT_EQ(f32At(s, r + 12 + 8 * 4), 0.5f);
}

TEST(Stl, LongHeadersAreCutAndTheStreamPositionIsKept) {
  std::stringstream out;
  out << "prefix";  // the writer may start mid-stream
  StlWriter w(out, std::string(100, 'h'));
  w.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  w.finish();
  const std::string s = out.str().substr(6);
  ASSERT_EQ(s.size(), 80u + 4 + 50);
  EXPECT_EQ(s.substr(0, 80), std::string(80, 'h'));
  EXPECT_EQ(u32At(s, 80), 1u);
}

TEST(Stl, EmptyMeshIsAValidFile) {
  std::stringstream out;
  StlWriter w(out);
  w.finish();
  EXPECT_EQ(out.str().size(), 84u);
  EXPECT_EQ(u32At(out.str(), 80), 0u);
}

TEST(Stl, DegenerateTriangleGetsAZeroNormal) {
  std::stringstream out;
  StlWriter w(out);
  w.add({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  w.finish();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(f32At(out.str(), 84 + 4 * i), 0.0f);
}

TEST(Stl, UnseekableStreamNeedsTheCountUpFront) {
  PipeBuf pipe;
  std::ostream out(&pipe);
  StlWriter w(out);
  w.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  try {
    w.finish();
    FAIL() << "finish() must refuse to leave a wrong count";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot seek"), std::string::npos) << e.what();
  }

  PipeBuf pipe2;
  std::ostream out2(&pipe2);
  StlWriter counted(out2, "pipe", 1);
  counted.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_NO_THROW(counted.finish());
  ASSERT_EQ(pipe2.data.size(), 134u);
  EXPECT_EQ(u32At(pipe2.data, 80), 1u);
}

TEST(Stl, BrokenPromiseIsAnError) {
  std::stringstream out;
  StlWriter w(out, "x", 3);
  w.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  try {
    w.finish();
    FAIL() << "a count of 3 with 1 triangle written must fail";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("promised 3"), std::string::npos) << e.what();
  }
}

TEST(Stl, FailedStreamIsReported) {
  std::stringstream out;
  StlWriter w(out);
  out.setstate(std::ios::badbit);
  w.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_THROW(w.finish(), std::runtime_error);
}

// Records are buffered and written a chunk at a time: thousands of triangles (several
// chunks and a partial one) come out whole and in order, through a pipe too.
TEST(Stl, ManyTrianglesComeOutInOrderAcrossChunks) {
  constexpr int kTriangles = 2500;
  PipeBuf pipe;
  std::ostream out(&pipe);
  StlWriter w(out, "many", kTriangles);
  for (int i = 0; i < kTriangles; ++i) w.add({i, 0, 0}, {i + 1.0, 0, 0}, {i, 1, 0});
  w.finish();
  ASSERT_EQ(pipe.data.size(), kStlHeaderBytes + 4 + kTriangles * kStlTriangleBytes);
  EXPECT_EQ(u32At(pipe.data, 80), std::uint32_t(kTriangles));
  for (int i = 0; i < kTriangles; ++i) {
    const std::size_t at = kStlHeaderBytes + 4 + i * kStlTriangleBytes;
    ASSERT_EQ(f32At(pipe.data, at + 12), float(i)) << i;      // first vertex x
    ASSERT_EQ(f32At(pipe.data, at + 24), float(i + 1)) << i;  // second vertex x
    ASSERT_EQ(pipe.data[at + 48], '\0');
    ASSERT_EQ(pipe.data[at + 49], '\0');
  }
}

// A writer dropped without finish() still hands on the records it took (the count
// stays the placeholder: finish() is what completes a file).
TEST(Stl, RecordsReachTheStreamWithoutFinish) {
  std::stringstream out;
  {
    StlWriter w(out);
    w.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  }
  EXPECT_EQ(out.str().size(), kStlHeaderBytes + 4 + kStlTriangleBytes);
}

}  // namespace
}  // namespace mdhd::protocol

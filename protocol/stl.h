#pragma once
// Binary STL out of the mesher, streaming: an 80-byte header, the triangle
// count (uint32), then per triangle its unit normal, three vertices (float32
// x y z, mm in the workpiece frame W) and a zero attribute word, all
// little-endian. Vertices are in the mesher's order, counter-clockwise seen
// from outside, and the normal is the right-hand one (outward).
//
// The count sits before the triangles: it is patched at the end when the
// stream can seek, or must be given up front (mesh once to count it) when it
// cannot (a pipe, a socket).
#include <cstdint>
#include <optional>
#include <ostream>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sim/mesh/mesh_sink.h"

namespace mdhd::protocol {

inline constexpr std::size_t kStlHeaderBytes = 80;
inline constexpr std::size_t kStlTriangleBytes = 50;

class StlWriter final : public mesh::MeshSink {
 public:
  // Writes the header (cut to 80 bytes, zero padded) and a count: `triangles`
  // if given, else a placeholder that finish() patches.
  explicit StlWriter(std::ostream& out, std::string_view header = "mdhd binary STL (mm)",
                     std::optional<std::uint32_t> triangles = std::nullopt);
  // Hands on what is buffered if finish() was not called (no count patched then).
  ~StlWriter() override;
  StlWriter(const StlWriter&) = delete;
  StlWriter& operator=(const StlWriter&) = delete;

  void triangle(const mesh::MeshVertex& a, const mesh::MeshVertex& b, const mesh::MeshVertex& c,
                bool exterior) override;
  void add(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

  // Completes the file. Throws std::runtime_error when the stream failed,
  // when a count given up front differs from the triangles written, when
  // more than 2^32 - 1 triangles were written, or when the count must be
  // patched and the stream cannot seek.
  void finish();
  std::uint64_t written() const { return written_; }

 private:
  std::ostream& out_;
  std::optional<std::uint32_t> promised_;
  std::ostream::pos_type countAt_;
  std::uint64_t written_ = 0;
  bool finished_ = false;
  // Records go to the stream a chunk at a time: one ostream::write per triangle (a
  // sentry and a virtual call each) cost 0.19 G instructions of the 3-axis dome's
  // meshing at density 10, on the thread that feeds the sink.
  void flushBuffer();
  std::vector<char> buffer_;
  std::size_t used_ = 0;
};

}  // namespace mdhd::protocol

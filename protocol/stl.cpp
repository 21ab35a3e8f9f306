#include "protocol/stl.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace mdhd::protocol {

namespace {

void putU32(char* at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) at[i] = static_cast<char>((v >> (8 * i)) & 0xffu);
}

void putF32(char* at, double v) {
  putU32(at, std::bit_cast<std::uint32_t>(static_cast<float>(v)));
}

void putVec(char* at, const glm::dvec3& v) {
  for (int i = 0; i < 3; ++i) putF32(at + 4 * i, v[i]);
}

constexpr std::size_t kBufferedTriangles = 1024;

}  // namespace

StlWriter::~StlWriter() {
  try {
    flushBuffer();
  } catch (...) {  // a stream set to throw: nothing to report to from here
  }
}

void StlWriter::flushBuffer() {
  if (used_ > 0) out_.write(buffer_.data(), static_cast<std::streamsize>(used_));
  used_ = 0;
}

StlWriter::StlWriter(std::ostream& out, std::string_view header,
                     std::optional<std::uint32_t> triangles)
    : out_(out), promised_(triangles) {
  std::array<char, kStlHeaderBytes> head{};
  std::memcpy(head.data(), header.data(), std::min(header.size(), head.size()));
  out_.write(head.data(), head.size());
  countAt_ = out_.tellp();
  char count[4];
  putU32(count, triangles.value_or(0));
  out_.write(count, 4);
}

void StlWriter::add(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  glm::dvec3 n = glm::cross(b - a, c - a);
  const double len = glm::length(n);
  n = len > 0.0 ? n / len : glm::dvec3(0.0);
  if (buffer_.empty()) buffer_.resize(kBufferedTriangles * kStlTriangleBytes);
  if (used_ == buffer_.size()) flushBuffer();
  char* rec = buffer_.data() + used_;
  putVec(rec, n);
  putVec(rec + 12, a);
  putVec(rec + 24, b);
  putVec(rec + 36, c);
  rec[48] = rec[49] = 0;  // the attribute word
  used_ += kStlTriangleBytes;
  ++written_;
}

void StlWriter::triangle(const mesh::MeshVertex& a, const mesh::MeshVertex& b,
                         const mesh::MeshVertex& c, bool /*exterior*/) {
  add(a.position, b.position, c.position);
}

void StlWriter::finish() {
  if (finished_) return;
  finished_ = true;
  flushBuffer();
  if (!out_) throw std::runtime_error("STL: the output stream failed while writing");
  if (written_ > std::numeric_limits<std::uint32_t>::max())
    throw std::runtime_error("STL: " + std::to_string(written_) +
                             " triangles do not fit the format's 32-bit count");
  if (promised_) {
    if (*promised_ != written_)
      throw std::runtime_error("STL: the header promised " + std::to_string(*promised_) +
                               " triangles but " + std::to_string(written_) + " were written");
    out_.flush();
    return;
  }
  const auto end = out_.tellp();
  if (countAt_ == std::ostream::pos_type(-1) || end == std::ostream::pos_type(-1))
    throw std::runtime_error(
        "STL: the stream cannot seek to patch the triangle count; give the count up front");
  char count[4];
  putU32(count, static_cast<std::uint32_t>(written_));
  out_.seekp(countAt_);
  out_.write(count, 4);
  out_.seekp(end);
  out_.flush();
  if (!out_) throw std::runtime_error("STL: could not patch the triangle count");
}

}  // namespace mdhd::protocol

#pragma once
// Seekable sources of program lines. The reader keeps only byte offsets of the
// places it must return to (loop starts, subroutine bodies), never the text,
// so a program of any length is read in constant memory.
#include <cstdint>
#include <istream>
#include <memory>
#include <string>

namespace mdhd::gcode {

class LineSource {
 public:
  virtual ~LineSource() = default;
  // Reads the next line without its newline (and a CR before it); false at end.
  virtual bool getLine(std::string& line) = 0;
  virtual std::uint64_t tell() const = 0;       // offset of the next line
  virtual void seek(std::uint64_t offset) = 0;  // to an offset tell() gave
  virtual int lineNumber() const = 0;           // 1-based number of the line last returned
  virtual void setLineNumber(int n) = 0;        // after a seek
};

// Longest line accepted: a file without newlines must not be read into memory
// whole. Longer lines throw GcodeError ("Line too long").
inline constexpr std::size_t kMaxLineLength = 64 * 1024;

std::unique_ptr<LineSource> makeStringSource(std::string text);
std::unique_ptr<LineSource> makeStreamSource(std::unique_ptr<std::istream> in);

}  // namespace mdhd::gcode

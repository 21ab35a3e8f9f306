#include "sim/gcode/source.h"

#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

#include "sim/gcode/error.h"

namespace mdhd::gcode {
namespace {

[[noreturn]] void failTooLong(int line) {
  throw GcodeError({"", line, kMaxLineLength + 1},
                   "Line too long (more than " + std::to_string(kMaxLineLength) + " characters)");
}

void stripCr(std::string& line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
}

class StringSource final : public LineSource {
 public:
  explicit StringSource(std::string text) : text_(std::move(text)) {}

  bool getLine(std::string& line) override {
    if (offset_ >= text_.size()) return false;
    std::string_view rest(text_);
    rest.remove_prefix(offset_);
    const std::size_t end = rest.find('\n');
    const std::size_t length = end == std::string_view::npos ? rest.size() : end;
    ++line_;
    if (length > kMaxLineLength + 1) failTooLong(line_);
    line.assign(rest.substr(0, length));
    offset_ += length + (end == std::string_view::npos ? 0 : 1);
    stripCr(line);
    return true;
  }
  std::uint64_t tell() const override { return offset_; }
  void seek(std::uint64_t offset) override { offset_ = offset; }
  int lineNumber() const override { return line_; }
  void setLineNumber(int n) override { line_ = n; }

 private:
  std::string text_;
  std::uint64_t offset_ = 0;
  int line_ = 0;
};

class StreamSource final : public LineSource {
 public:
  explicit StreamSource(std::unique_ptr<std::istream> in) : in_(std::move(in)), buffer_(kChunk) {}

  bool getLine(std::string& line) override {
    line.clear();
    bool any = false;
    for (;;) {
      if (begin_ == end_ && !refill()) break;
      any = true;
      const char* start = buffer_.data() + begin_;
      const std::size_t available = end_ - begin_;
      const void* newline = std::memchr(start, '\n', available);
      const std::size_t take =
          newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - start) : available;
      if (line.size() + take > kMaxLineLength + 1) failTooLong(line_ + 1);
      line.append(start, take);
      begin_ += take;
      offset_ += take;
      if (newline) {
        ++begin_;
        ++offset_;
        break;
      }
    }
    if (!any) return false;
    ++line_;
    stripCr(line);
    return true;
  }
  std::uint64_t tell() const override { return offset_; }
  void seek(std::uint64_t offset) override {
    in_->clear();
    in_->seekg(static_cast<std::streamoff>(offset));
    begin_ = end_ = 0;
    offset_ = offset;
  }
  int lineNumber() const override { return line_; }
  void setLineNumber(int n) override { line_ = n; }

 private:
  static constexpr std::size_t kChunk = 64 * 1024;

  bool refill() {
    if (!*in_) return false;
    in_->read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    begin_ = 0;
    end_ = static_cast<std::size_t>(in_->gcount());
    return end_ > 0;
  }

  std::unique_ptr<std::istream> in_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  std::uint64_t offset_ = 0;
  int line_ = 0;
};

}  // namespace

std::unique_ptr<LineSource> makeStringSource(std::string text) {
  return std::make_unique<StringSource>(std::move(text));
}

std::unique_ptr<LineSource> makeStreamSource(std::unique_ptr<std::istream> in) {
  return std::make_unique<StreamSource>(std::move(in));
}

}  // namespace mdhd::gcode

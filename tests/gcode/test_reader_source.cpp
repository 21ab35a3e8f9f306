// Line sources: lines, line numbers, offsets and seeking, for strings and streams.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "sim/gcode/error.h"
#include "sim/gcode/source.h"

namespace mdhd::gcode {
namespace {

using SourceFactory = std::unique_ptr<LineSource> (*)(std::string);

std::unique_ptr<LineSource> fromString(std::string text) {
  return makeStringSource(std::move(text));
}
std::unique_ptr<LineSource> fromStream(std::string text) {
  return makeStreamSource(std::make_unique<std::istringstream>(std::move(text)));
}

class LineSourceTest : public ::testing::TestWithParam<SourceFactory> {};

TEST_P(LineSourceTest, LinesNumbersAndOffsets) {
  auto source = GetParam()("G0 X1\r\n\nlast without newline");
  std::string line;
  EXPECT_EQ(source->tell(), 0u);
  ASSERT_TRUE(source->getLine(line));
  EXPECT_EQ(line, "G0 X1");
  EXPECT_EQ(source->lineNumber(), 1);
  EXPECT_EQ(source->tell(), 7u);
  ASSERT_TRUE(source->getLine(line));
  EXPECT_EQ(line, "");
  EXPECT_EQ(source->lineNumber(), 2);
  const std::uint64_t third = source->tell();
  EXPECT_EQ(third, 8u);
  ASSERT_TRUE(source->getLine(line));
  EXPECT_EQ(line, "last without newline");
  EXPECT_EQ(source->lineNumber(), 3);
  EXPECT_FALSE(source->getLine(line));
  EXPECT_FALSE(source->getLine(line));  // stays at the end

  // Back to an offset it gave, also after reaching the end.
  source->seek(third);
  source->setLineNumber(2);
  ASSERT_TRUE(source->getLine(line));
  EXPECT_EQ(line, "last without newline");
  EXPECT_EQ(source->lineNumber(), 3);
  source->seek(0);
  source->setLineNumber(0);
  ASSERT_TRUE(source->getLine(line));
  EXPECT_EQ(line, "G0 X1");
  EXPECT_EQ(source->lineNumber(), 1);
}

TEST_P(LineSourceTest, EmptyText) {
  auto source = GetParam()("");
  std::string line;
  EXPECT_FALSE(source->getLine(line));
  EXPECT_EQ(source->lineNumber(), 0);
}

TEST_P(LineSourceTest, LinesLongerThanTheStreamBufferAreWhole) {
  auto source = GetParam()("a\n" + std::string(60'000, 'y') + "\nb\n");
  std::string line;
  ASSERT_TRUE(source->getLine(line));
  ASSERT_TRUE(source->getLine(line));
  EXPECT_EQ(line.size(), 60'000u);
  ASSERT_TRUE(source->getLine(line));
  EXPECT_EQ(line, "b");
  EXPECT_EQ(source->lineNumber(), 3);
}

TEST_P(LineSourceTest, OverlongLineIsAnError) {
  auto source = GetParam()("ok\n" + std::string(kMaxLineLength + 10, 'x') + "\n");
  std::string line;
  ASSERT_TRUE(source->getLine(line));
  try {
    source->getLine(line);
    FAIL() << "no error";
  } catch (const GcodeError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_STREQ(e.what(), "Line too long (more than 65536 characters)");
  }
}

// Named, so ctest's names stay the same from build to build (not pointer values).
INSTANTIATE_TEST_SUITE_P(Sources, LineSourceTest, ::testing::Values(&fromString, &fromStream),
                         [](const auto& p) {
                           return std::string(p.param == &fromString ? "String" : "Stream");
                         });

}  // namespace
}  // namespace mdhd::gcode

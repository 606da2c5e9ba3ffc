#include <gtest/gtest.h>

#include "frontend/diagnostics/source.h"

namespace {

namespace fe = openplx::frontend;

TEST(SourceFile, LineAndColumnAreOneBased) {
  fe::SourceFile file("a.openplx", "ab\ncd\n");
  EXPECT_EQ(file.line_col(0).line, 1u);
  EXPECT_EQ(file.line_col(0).col, 1u);
  EXPECT_EQ(file.line_col(4).line, 2u);
  EXPECT_EQ(file.line_col(4).col, 2u);
  EXPECT_EQ(file.line_text(2), "cd");
}

TEST(SourceFile, CrlfAndLoneCrEndLines) {
  fe::SourceFile file("a.openplx", "a\r\nb\rc");
  EXPECT_EQ(file.line_count(), 3u);
  EXPECT_EQ(file.line_text(1), "a");
  EXPECT_EQ(file.line_text(2), "b");
  EXPECT_EQ(file.line_col(5).line, 3u);
}

TEST(SourceFile, ByteOrderMarkIsNotPartOfTheFirstLine) {
  fe::SourceFile file("a.openplx", "\xEF\xBB\xBFRoot");
  EXPECT_EQ(file.content_begin(), 3u);
  EXPECT_EQ(file.line_col(3).col, 1u);
  EXPECT_EQ(file.line_text(1), "Root");
}

}  // namespace

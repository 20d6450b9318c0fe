#include "support/source_manager.h"

#include <gtest/gtest.h>

namespace spire {
namespace {

TEST(SourceManager, LineAndColumnForLfAndCrlf) {
  SourceManager sm;
  const FileId lf = sm.addFile("a.spire", "ab\ncd\n");
  const FileId crlf = sm.addFile("b.spire", "ab\r\ncd\r\n");
  EXPECT_EQ(sm.lineCol(lf, 4).line, 2u);
  EXPECT_EQ(sm.lineCol(lf, 4).column, 2u);
  EXPECT_EQ(sm.lineCol(crlf, 5).line, 2u);
  EXPECT_EQ(sm.lineCol(crlf, 5).column, 2u);
  EXPECT_EQ(sm.lineText(crlf, 1), "ab");
  EXPECT_EQ(sm.lineText(crlf, 2), "cd");
  EXPECT_EQ(sm.lineText(crlf, 3), "");
}

TEST(SourceManager, ColumnsCountCodePoints) {
  SourceManager sm;
  const FileId f = sm.addFile("u.spire", "// \xC3\xA9t\xC3\xA9\nx");
  // 'é' is two bytes but one column.
  EXPECT_EQ(sm.lineCol(f, 5).column, 5u);
}

TEST(SourceManager, OffsetsPastTheEndClamp) {
  SourceManager sm;
  const FileId f = sm.addFile("e.spire", "abc");
  EXPECT_EQ(sm.lineCol(f, 100).column, 4u);
  EXPECT_EQ(sm.text({f, 2, 100}), "c");
}

}  // namespace
}  // namespace spire

#include "support/depfile.h"

#include <gtest/gtest.h>

namespace spire {
namespace {

std::string escaped(std::string_view path) { return escapeMakePath(path).value(); }

TEST(Depfile, EscapesWhatMakeAndNinjaWouldSplitOrExpand) {
  EXPECT_EQ(escaped("shaders/lit.spire"), "shaders/lit.spire");
  EXPECT_EQ(escaped("my shaders/a b.spire"), "my\\ shaders/a\\ b.spire");
  EXPECT_EQ(escaped("take#2/x.spire"), "take\\#2/x.spire");
  EXPECT_EQ(escaped("$HOME/x.spire"), "$$HOME/x.spire");
  // Backslashes before a space are doubled, then the space gets its own.
  EXPECT_EQ(escaped("a\\ b"), "a\\\\\\ b");
  EXPECT_EQ(escaped("a\\b"), "a\\b");
}

TEST(Depfile, APathWithANewlineCannotBeWritten) {
  const auto result = escapeMakePath("bad\nname.spire");
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("newline"), std::string::npos) << result.error().message;
  EXPECT_FALSE(makeDepfile("out", {"a.spire", "bad\nname.spire"}));
  EXPECT_FALSE(makeDepfile("out\n", {"a.spire"}));
}

TEST(Depfile, OneRuleWithEachPrerequisiteOnce) {
  EXPECT_EQ(makeDepfile("out dir", {"a.spire", "lib/b.spire", "a.spire"}).value(),
            "out\\ dir: \\\n  a.spire \\\n  lib/b.spire\n");
  EXPECT_EQ(makeDepfile("stamp", {}).value(), "stamp:\n");
}

}  // namespace
}  // namespace spire

#include "support/spelling.h"

#include <gtest/gtest.h>

namespace spire {
namespace {

TEST(Spelling, EditDistance) {
  EXPECT_EQ(editDistance("mixFactor", "mixFactor"), 0u);
  EXPECT_EQ(editDistance("mixFactr", "mixFactor"), 1u);
  EXPECT_EQ(editDistance("Vertx", "Vertex"), 1u);
  EXPECT_EQ(editDistance("ab", "ba"), 1u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
}

TEST(Spelling, SuggestsOnlyPlausibleNames) {
  const std::vector<std::string_view> worlds = {"FrameUniform", "Vertex", "Fragment", "PrebakeTex"};
  EXPECT_EQ(closestSpelling("Fragmnet", worlds), "Fragment");
  EXPECT_EQ(closestSpelling("vertex", worlds), "Vertex");
  EXPECT_EQ(closestSpelling("Zzz", worlds), std::nullopt);
}

}  // namespace
}  // namespace spire

// The per-view error every tool measures with (renderer/view_error.h).
#include "renderer/view_error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spire::engine {
namespace {

// A 2x1 capture: both pixels grey `value`, `coverage` per pixel.
Capture capture(float value, std::vector<uint8_t> coverage) {
  Capture c;
  c.color = {2, 1, std::vector<float>(8, value)};
  c.coverage = std::move(coverage);
  return c;
}

TEST(ViewError, CountsPixelsEitherImageCovers) {
  const auto error = viewError(capture(0.0F, {1, 0}), capture(0.5F, {0, 1}));
  ASSERT_TRUE(error) << error.error().message;
  EXPECT_EQ(error->coveredPixels, 2U);
  EXPECT_DOUBLE_EQ(error->rmse, 0.5);
  const auto none = viewError(capture(0.0F, {0, 0}), capture(0.5F, {0, 0}));
  ASSERT_TRUE(none);
  EXPECT_EQ(none->coveredPixels, 0U);
}

TEST(ViewError, CombinesViewsOverAllTheirPixels) {
  const std::vector<Capture> reference{capture(0.0F, {1, 1}), capture(0.0F, {1, 0})};
  const std::vector<Capture> test{capture(0.0F, {1, 1}), capture(0.3F, {1, 0})};
  const auto error = viewsError(reference, test);
  ASSERT_TRUE(error) << error.error().message;
  EXPECT_EQ(error->coveredPixels, 3U);
  // One pixel of three is off by 0.3 in every channel.
  EXPECT_NEAR(error->rmse, std::sqrt(0.09 / 3.0), 1e-6);
}

TEST(ViewError, MismatchedCapturesAreErrors) {
  EXPECT_FALSE(viewError(capture(0.0F, {1, 1}), capture(0.0F, {1})));
  const std::vector<Capture> one{capture(0.0F, {1, 1})};
  const std::vector<Capture> two{capture(0.0F, {1, 1}), capture(0.0F, {1, 1})};
  EXPECT_FALSE(viewsError(one, two));
}

}  // namespace
}  // namespace spire::engine

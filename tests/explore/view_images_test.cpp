// The explorer's derived views, pixel by pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "explore/view_images.h"

namespace spire::explore {
namespace {

measure::FloatImage solid(uint32_t width, uint32_t height, float value) {
  measure::FloatImage image{width, height, std::vector<float>(static_cast<size_t>(width) * height * 4, value)};
  for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 1.0F;
  return image;
}

std::vector<float> pixel(const measure::FloatImage& image, size_t i) {
  return {image.rgba[i * 4], image.rgba[i * 4 + 1], image.rgba[i * 4 + 2], image.rgba[i * 4 + 3]};
}

TEST(ViewImages, HeatMapRampsTheLargestChannelDifference) {
  const measure::FloatImage reference = solid(4, 1, 0.5F);
  measure::FloatImage variant = reference;
  variant.rgba[1 * 4 + 1] = 0.5F + 0.25F / 3.0F;  // a third of the scale: pure blue
  variant.rgba[2 * 4 + 0] = 0.0F;                 // beyond the scale: yellow
  variant.rgba[3 * 4 + 2] = std::numeric_limits<float>::quiet_NaN();
  const std::vector<uint8_t> coverage{1, 1, 1, 1};
  const measure::FloatImage heat = errorHeatMap(reference, variant, coverage, 0.25F);
  EXPECT_EQ(pixel(heat, 0), (std::vector<float>{0, 0, 0, 1}));
  EXPECT_NEAR(pixel(heat, 1)[2], 1.0F, 1e-5F);
  EXPECT_EQ(pixel(heat, 2), (std::vector<float>{1, 1, 0, 1}));
  EXPECT_EQ(pixel(heat, 3), (std::vector<float>{1, 0, 1, 1}));
  const measure::FloatImage uncovered = errorHeatMap(reference, variant, {0, 1, 1, 1}, 0.25F);
  EXPECT_EQ(pixel(uncovered, 0), (std::vector<float>{0.25F, 0.25F, 0.25F, 1}));
}

TEST(ViewImages, HazardMaskMarksNaNAndInf) {
  measure::FloatImage variant = solid(3, 1, 1.0F);
  variant.rgba[0] = std::numeric_limits<float>::quiet_NaN();
  variant.rgba[4 + 3] = std::numeric_limits<float>::infinity();
  const measure::FloatImage mask = hazardMask(variant);
  EXPECT_EQ(pixel(mask, 0), (std::vector<float>{1, 0, 1, 1}));
  EXPECT_EQ(pixel(mask, 1), (std::vector<float>{1, 1, 1, 1}));
  EXPECT_NEAR(pixel(mask, 2)[0], 0.3F, 1e-6F);
}

TEST(ViewImages, SplitShowsTheReferenceLeftAndTheVariantRight) {
  const measure::FloatImage split = splitImage(solid(8, 2, 0.2F), solid(8, 2, 0.7F));
  EXPECT_FLOAT_EQ(pixel(split, 0)[0], 0.2F);
  EXPECT_FLOAT_EQ(pixel(split, 2)[0], 0.2F);
  EXPECT_FLOAT_EQ(pixel(split, 3)[0], 1.0F);  // the line
  EXPECT_FLOAT_EQ(pixel(split, 4)[0], 1.0F);
  EXPECT_FLOAT_EQ(pixel(split, 5)[0], 0.7F);
  EXPECT_FLOAT_EQ(pixel(split, 8 + 1)[0], 0.2F);
}

}  // namespace
}  // namespace spire::explore

#include "measure/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace spire::measure {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

FloatImage uniform(uint32_t width, uint32_t height, float r, float g, float b, float a = 1.0F) {
  FloatImage image{width, height, {}};
  for (uint32_t p = 0; p < width * height; ++p) image.rgba.insert(image.rgba.end(), {r, g, b, a});
  return image;
}

void setPixel(FloatImage& image, uint32_t x, uint32_t y, float r, float g, float b, float a = 1.0F) {
  float* px = &image.rgba[(static_cast<size_t>(y) * image.width + x) * 4];
  px[0] = r;
  px[1] = g;
  px[2] = b;
  px[3] = a;
}

ImageError compare(const FloatImage& reference, const FloatImage& test,
                   const std::vector<uint8_t>* coverage = nullptr) {
  auto error = compareImages(reference, test, coverage);
  EXPECT_TRUE(error) << error.error().message;
  return error ? *error : ImageError{};
}

void expectBroken(const ImageError& error) {
  EXPECT_EQ(error.rmse, kInfinity);
  EXPECT_EQ(error.maxError, kInfinity);
  EXPECT_EQ(error.psnr, 0.0);
}

TEST(ImageMetricsTest, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  FloatImage image = uniform(4, 3, 0.2F, 0.4F, 0.6F);
  setPixel(image, 1, 2, 3.5F, -1.0F, 0.0F);  // raw values outside [0, 1] are fine
  ImageError error = compare(image, image);
  EXPECT_EQ(error.rmse, 0.0);
  EXPECT_EQ(error.maxError, 0.0);
  EXPECT_EQ(error.psnr, kInfinity);
  EXPECT_EQ(error.coveredPixels, 12u);
  EXPECT_EQ(error.nanPixels + error.infPixels, 0u);
  EXPECT_FALSE(error.hasHazards());
}

TEST(ImageMetricsTest, KnownOffsetGivesExactRmseAndPsnr) {
  // Binary fractions, so every difference is exact.
  FloatImage reference = uniform(5, 2, 0.25F, 0.5F, 0.75F, 1.0F);
  FloatImage test = uniform(5, 2, 0.375F, 0.375F, 0.875F, 0.0F);  // alpha differs and is ignored
  ImageError error = compare(reference, test);
  EXPECT_DOUBLE_EQ(error.rmse, 0.125);
  EXPECT_DOUBLE_EQ(error.maxError, 0.125);
  EXPECT_DOUBLE_EQ(error.psnr, -20.0 * std::log10(0.125));
  EXPECT_DOUBLE_EQ(error.sumSquaredError, 30 * 0.125 * 0.125);
}

TEST(ImageMetricsTest, SingleChannelErrorIsAveragedOverAllChannels) {
  FloatImage reference = uniform(2, 2, 0.5F, 0.5F, 0.5F);
  FloatImage test = reference;
  setPixel(test, 1, 1, 0.5F, 1.0F, 0.5F);
  ImageError error = compare(reference, test);
  EXPECT_DOUBLE_EQ(error.rmse, std::sqrt(0.25 / 12.0));
  EXPECT_DOUBLE_EQ(error.maxError, 0.5);
}

TEST(ImageMetricsTest, NaNAndInfAreCountedAndNeverAveragedAway) {
  FloatImage reference = uniform(100, 100, 0.5F, 0.5F, 0.5F);
  FloatImage test = reference;
  setPixel(test, 3, 4, 0.5F, kNaN, 0.5F);
  setPixel(test, 5, 6, 0.5F, 0.5F, 0.5F, kNaN);  // alpha counts too
  setPixel(test, 7, 8, kInf, 0.5F, 0.5F);
  setPixel(test, 9, 9, -kInf, 0.5F, 0.5F);
  setPixel(test, 1, 1, kInf, kNaN, 0.5F);  // both: counted as NaN
  ImageError error = compare(reference, test);
  EXPECT_EQ(error.nanPixels, 3u);
  EXPECT_EQ(error.infPixels, 2u);
  EXPECT_EQ(error.referenceNanPixels + error.referenceInfPixels, 0u);
  EXPECT_TRUE(error.hasHazards());
  expectBroken(error);
}

TEST(ImageMetricsTest, ReferenceHazardsAreCountedSeparately) {
  FloatImage reference = uniform(3, 3, 0.5F, 0.5F, 0.5F);
  FloatImage test = reference;
  setPixel(reference, 0, 0, kNaN, 0.5F, 0.5F);
  setPixel(reference, 1, 0, kInf, 0.5F, 0.5F);
  setPixel(reference, 2, 0, kInf, 0.5F, 0.5F);
  ImageError error = compare(reference, test);
  EXPECT_EQ(error.nanPixels + error.infPixels, 0u);
  EXPECT_EQ(error.referenceNanPixels, 1u);
  EXPECT_EQ(error.referenceInfPixels, 2u);
  expectBroken(error);
}

TEST(ImageMetricsTest, CoverageMaskSelectsPixels) {
  FloatImage reference = uniform(2, 2, 0.0F, 0.0F, 0.0F);
  FloatImage test = reference;
  setPixel(test, 0, 0, 0.5F, 0.5F, 0.5F);  // covered
  setPixel(test, 1, 0, 1.0F, 1.0F, 1.0F);  // not covered: ignored
  std::vector<uint8_t> coverage = {1, 0, 255, 0};
  ImageError error = compare(reference, test, &coverage);
  EXPECT_EQ(error.coveredPixels, 2u);
  EXPECT_DOUBLE_EQ(error.rmse, std::sqrt(3 * 0.25 / 6.0));
  EXPECT_DOUBLE_EQ(error.maxError, 0.5);

  std::vector<uint8_t> nothing(4, 0);
  ImageError empty = compare(reference, test, &nothing);
  EXPECT_EQ(empty.coveredPixels, 0u);
  EXPECT_EQ(empty.rmse, 0.0);
  EXPECT_EQ(empty.psnr, kInfinity);
}

TEST(ImageMetricsTest, HazardOutsideCoverageStillBreaksTheComparison) {
  FloatImage reference = uniform(2, 1, 0.0F, 0.0F, 0.0F);
  FloatImage test = reference;
  setPixel(test, 1, 0, kNaN, 0.0F, 0.0F);
  std::vector<uint8_t> coverage = {1, 0};
  ImageError error = compare(reference, test, &coverage);
  EXPECT_EQ(error.nanPixels, 1u);
  expectBroken(error);
}

TEST(ImageMetricsTest, AccumulatorIsExactOverAllViews) {
  // View A: 1 pixel off by 0.5 in every channel; view B: 8 identical pixels.
  ImageError a = compare(uniform(1, 1, 0.0F, 0.0F, 0.0F), uniform(1, 1, 0.5F, 0.5F, 0.5F));
  ImageError b = compare(uniform(8, 1, 0.25F, 0.25F, 0.25F), uniform(8, 1, 0.25F, 0.25F, 0.25F));
  ErrorAccumulator accumulator;
  accumulator.add(a);
  accumulator.add(b);
  ImageError total = accumulator.total();
  EXPECT_EQ(total.coveredPixels, 9u);
  // sqrt(3 * 0.25 / 27) = 1/6, where the mean of the views' RMSEs would be 0.25.
  EXPECT_DOUBLE_EQ(total.rmse, 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(total.maxError, 0.5);
  EXPECT_DOUBLE_EQ(total.psnr, 20.0 * std::log10(6.0));

  FloatImage hazard = uniform(1, 1, 0.0F, 0.0F, 0.0F);
  setPixel(hazard, 0, 0, kInf, 0.0F, 0.0F);
  accumulator.add(compare(uniform(1, 1, 0.0F, 0.0F, 0.0F), hazard));
  total = accumulator.total();
  EXPECT_EQ(total.infPixels, 1u);
  expectBroken(total);

  ImageError none = ErrorAccumulator{}.total();
  EXPECT_EQ(none.rmse, 0.0);
  EXPECT_EQ(none.psnr, kInfinity);
}

TEST(ImageMetricsTest, MismatchedInputsAreErrors) {
  FloatImage small = uniform(2, 2, 0.0F, 0.0F, 0.0F);
  FloatImage wide = uniform(3, 2, 0.0F, 0.0F, 0.0F);
  auto sizes = compareImages(small, wide, nullptr);
  ASSERT_FALSE(sizes);
  EXPECT_NE(sizes.error().message.find("3x2"), std::string::npos) << sizes.error().message;
  EXPECT_NE(sizes.error().message.find("2x2"), std::string::npos) << sizes.error().message;

  std::vector<uint8_t> shortMask(3, 1);
  EXPECT_FALSE(compareImages(small, small, &shortMask));

  FloatImage truncated = small;
  truncated.rgba.pop_back();
  EXPECT_FALSE(compareImages(small, truncated, nullptr));
  EXPECT_FALSE(compareImages(truncated, small, nullptr));
}

TEST(ImageMetricsTest, ToRgba8RoundsAndClamps) {
  FloatImage image = uniform(2, 1, 0.5F, 0.2F, -0.5F, 2.0F);
  setPixel(image, 1, 0, 1.0F, 0.0F, 0.998F, 0.002F);
  scene::Image out = toRgba8(image);
  ASSERT_EQ(out.width, 2u);
  ASSERT_EQ(out.height, 1u);
  EXPECT_EQ(out.pixel(0, 0), scene::Rgba8(128, 51, 0, 255));  // 127.5 rounds up, 51.0 stays
  EXPECT_EQ(out.pixel(1, 0), scene::Rgba8(255, 0, 254, 1));
}

TEST(ImageMetricsTest, ToRgba8PaintsHazards) {
  FloatImage image = uniform(4, 1, 0.1F, 0.2F, 0.3F, 0.5F);
  setPixel(image, 0, 0, 0.1F, kNaN, 0.3F, 0.5F);
  setPixel(image, 1, 0, kInf, 0.2F, 0.3F, 0.5F);
  setPixel(image, 2, 0, 0.1F, -kInf, 0.3F, 0.5F);
  setPixel(image, 3, 0, kInf, 0.2F, kNaN, 0.5F);
  scene::Image out = toRgba8(image);
  EXPECT_EQ(out.pixel(0, 0), scene::Rgba8(255, 0, 255, 255));
  EXPECT_EQ(out.pixel(1, 0), scene::Rgba8(255, 255, 255, 255));
  EXPECT_EQ(out.pixel(2, 0), scene::Rgba8(255, 255, 255, 255));
  EXPECT_EQ(out.pixel(3, 0), scene::Rgba8(255, 0, 255, 255));  // NaN wins over Inf

  FloatImage broken = image;
  broken.rgba.resize(3);
  scene::Image empty = toRgba8(broken);
  EXPECT_EQ(empty.width, 0u);
  EXPECT_TRUE(empty.bytes.empty());
}

}  // namespace
}  // namespace spire::measure

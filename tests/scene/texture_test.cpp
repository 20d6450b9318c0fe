#include "scene/texture.h"

#include "temp_dir.h"

#include <gtest/gtest.h>

#include <stb/stb_image_write.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace spire::scene {
namespace {

using testing::TempDir;

const Rgba8 kRed(255, 0, 0, 255);
const Rgba8 kBlue(0, 0, 255, 128);

TEST(TextureTest, CheckerExactPixels) {
  Image image = makeChecker(8, 4, kRed, kBlue);  // 2x2-pixel cells
  ASSERT_EQ(image.width, 8u);
  ASSERT_EQ(image.height, 8u);
  ASSERT_EQ(image.rgba8.size(), 8u * 8u * 4u);
  for (uint32_t y = 0; y < 8; ++y) {
    for (uint32_t x = 0; x < 8; ++x) {
      Rgba8 expected = ((x / 2) + (y / 2)) % 2 == 0 ? kRed : kBlue;
      EXPECT_EQ(image.pixel(x, y), expected) << x << "," << y;
    }
  }
}

TEST(TextureTest, SolidIsUniform) {
  Image image = makeSolid(5, kBlue);
  for (uint32_t y = 0; y < 5; ++y) {
    for (uint32_t x = 0; x < 5; ++x) EXPECT_EQ(image.pixel(x, y), kBlue);
  }
}

TEST(TextureTest, NoiseStatisticsAndDeterminism) {
  Image image = makeNoise(64, 11, 5);
  double sum = 0.0;
  uint8_t lo = 255;
  uint8_t hi = 0;
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      Rgba8 p = image.pixel(x, y);
      EXPECT_TRUE(p.r == p.g && p.g == p.b && p.a == 255);
      sum += p.r;
      lo = std::min(lo, p.r);
      hi = std::max(hi, p.r);
    }
  }
  double mean = sum / (64.0 * 64.0);
  EXPECT_GT(mean, 80.0);
  EXPECT_LT(mean, 175.0);
  EXPECT_GT(hi - lo, 60) << "noise should have contrast";
  EXPECT_EQ(makeNoise(64, 11, 5).rgba8, image.rgba8);
  EXPECT_NE(makeNoise(64, 12, 5).rgba8, image.rgba8);
}

TEST(TextureTest, NormalMapDecodesToUnitUpwardNormals) {
  Image image = makeNormalMap(32, 5, 2.0f);
  bool tilted = false;
  for (uint32_t y = 0; y < 32; ++y) {
    for (uint32_t x = 0; x < 32; ++x) {
      Rgba8 p = image.pixel(x, y);
      glm::vec3 n = glm::vec3(p.r, p.g, p.b) / 255.0f * 2.0f - 1.0f;
      EXPECT_NEAR(glm::length(n), 1.0f, 0.02f);  // 8-bit quantisation
      EXPECT_GT(n.z, 0.0f);
      tilted = tilted || n.z < 0.98f;
    }
  }
  EXPECT_TRUE(tilted) << "strength 2 should tilt some normals";
  // Zero strength is a flat map: (0, 0, 1) encodes to (128, 128, 255).
  EXPECT_EQ(makeNormalMap(4, 5, 0.0f).pixel(1, 2), Rgba8(128, 128, 255, 255));
}

// The 16-bit value of a GGX table texel (R high byte, G low byte), in [0, 1].
double ggxLutValue(const Image& lut, uint32_t x, uint32_t y) {
  Rgba8 p = lut.pixel(x, y);
  return (p.r * 256.0 + p.g) / 65535.0;
}

// GGX D(n.h, alpha) written the usual way, to check the table against a
// formula other than the one it was made with.
double ggxDistribution(double nDotH, double alpha) {
  const double pi = 3.14159265358979;
  double alpha2 = alpha * alpha;
  double denom = nDotH * nDotH * (alpha2 - 1.0) + 1.0;
  return alpha2 / (pi * denom * denom);
}

TEST(TextureTest, GgxLutTabulatesTheDistributionOverItsPeak) {
  constexpr uint32_t kSize = 64;
  Image lut = makeGgxLut(kSize);
  ASSERT_EQ(lut.width, kSize);
  ASSERT_EQ(lut.height, kSize);
  for (uint32_t y = 0; y < kSize; ++y) {
    double roughness = (y + 0.5) / kSize;
    double alpha = std::max(roughness * roughness, static_cast<double>(kGgxMinAlpha));
    double peak = ggxDistribution(1.0, alpha);
    for (uint32_t x = 0; x < kSize; ++x) {
      Rgba8 p = lut.pixel(x, y);
      EXPECT_EQ(p.b, 0);
      EXPECT_EQ(p.a, 255);
      double sinTheta = (x + 0.5) / kSize;
      double expected = ggxDistribution(std::sqrt(1.0 - sinTheta * sinTheta), alpha) / peak;
      // Half a step of the 16-bit encoding, plus double rounding in the formulas.
      EXPECT_NEAR(ggxLutValue(lut, x, y), expected, 0.5 / 65535.0 + 1e-9) << x << "," << y;
      // The distribution falls away from the peak (or stays at 0 in 16 bits).
      if (x > 0) {
        EXPECT_LE(ggxLutValue(lut, x, y), ggxLutValue(lut, x - 1, y)) << x << "," << y;
      }
    }
  }
}

TEST(TextureTest, GgxLutKeepsTheTailsThatEightBitsWouldLose) {
  Image lut = makeGgxLut(256);
  // Roughness 0.4 at 60 degrees off the normal (leather's highlight tail): D
  // is 0.12% of its peak, under a third of an 8-bit step, and 76 16-bit steps.
  uint32_t row = 102;     // roughness (102 + 0.5) / 256, about 0.4
  uint32_t column = 221;  // sin(theta_h) (221 + 0.5) / 256, about 0.865 (60 degrees)
  EXPECT_EQ(lut.pixel(column, row), Rgba8(0, 76, 0, 255));
  // The peak texel of the roughest row is (almost) exactly 1.
  EXPECT_GT(ggxLutValue(lut, 0, 255), 0.9999);
}

TEST(ImageFileTest, PngRoundTripIsBitExact) {
  TempDir dir;
  Image original = makeNoise(33, 3, 4);  // odd size catches stride mistakes
  original.rgba8[3] = 7;                 // non-opaque alpha must survive too
  auto path = dir.path() / "noise.png";
  auto written = writePng(path, original);
  ASSERT_TRUE(written) << written.error().message;
  auto loaded = loadImage(path);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->width, 33u);
  EXPECT_EQ(loaded->height, 33u);
  EXPECT_EQ(loaded->rgba8, original.rgba8);
  // Only the target remains: the temporary file was renamed away.
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);
}

TEST(ImageFileTest, LoadsJpeg) {
  TempDir dir;
  // JPEG is lossy, so a solid colour checks decoding within a tolerance.
  Image solid = makeSolid(16, Rgba8(200, 100, 50, 255));
  auto path = dir.path() / "solid.jpg";
  ASSERT_NE(stbi_write_jpg(path.c_str(), 16, 16, 4, solid.rgba8.data(), 100), 0);
  auto loaded = loadImage(path);
  ASSERT_TRUE(loaded) << loaded.error().message;
  ASSERT_EQ(loaded->width, 16u);
  Rgba8 p = loaded->pixel(7, 9);
  EXPECT_NEAR(p.r, 200, 3);
  EXPECT_NEAR(p.g, 100, 3);
  EXPECT_NEAR(p.b, 50, 3);
  EXPECT_EQ(p.a, 255);
}

TEST(ImageFileTest, WritePngReplacesExistingFile) {
  TempDir dir;
  auto path = dir.path() / "image.png";
  ASSERT_TRUE(writePng(path, makeSolid(4, kRed)));
  ASSERT_TRUE(writePng(path, makeSolid(4, kBlue)));
  auto loaded = loadImage(path);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->pixel(0, 0), kBlue);
}

TEST(ImageFileTest, WritePngRejectsInconsistentImage) {
  TempDir dir;
  Image broken{4, 4, std::vector<uint8_t>(10)};
  auto path = dir.path() / "broken.png";
  auto written = writePng(path, broken);
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos) << written.error().message;
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ImageFileTest, WritePngIntoMissingDirectoryFails) {
  TempDir dir;
  auto path = dir.path() / "no" / "such" / "dir.png";
  auto written = writePng(path, makeSolid(2, kRed));
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos) << written.error().message;
}

TEST(ImageFileTest, MissingFileErrorNamesPath) {
  TempDir dir;
  auto path = dir.path() / "missing.png";
  auto loaded = loadImage(path);
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().message.find(path.string()), std::string::npos) << loaded.error().message;
  EXPECT_NE(loaded.error().message.find("does not exist"), std::string::npos) << loaded.error().message;
}

TEST(ImageFileTest, CorruptFileErrorNamesPath) {
  TempDir dir;
  auto path = dir.path() / "corrupt.png";
  {
    std::ofstream out(path, std::ios::binary);
    out << "\x89PNG\r\n\x1a\n this is not a real PNG stream";
  }
  auto loaded = loadImage(path);
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().message.find(path.string()), std::string::npos) << loaded.error().message;
}

}  // namespace
}  // namespace spire::scene

#include "scene/texture.h"

#include "temp_dir.h"

#include <gtest/gtest.h>

#include <stb/stb_image_write.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

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

TEST(ImageFileTest, PngRoundTripIsBitExact) {
  TempDir dir;
  Image original = makeNoise(33, 3, 4);  // odd size catches stride mistakes
  original.rgba8[3] = 7;                 // non-opaque alpha must survive too
  auto path = dir.path() / "noise.png";
  auto written = writePng(path, original);
  ASSERT_TRUE(written) << written.error();
  auto loaded = loadImage(path);
  ASSERT_TRUE(loaded) << loaded.error();
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
  ASSERT_TRUE(loaded) << loaded.error();
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
  ASSERT_TRUE(loaded) << loaded.error();
  EXPECT_EQ(loaded->pixel(0, 0), kBlue);
}

TEST(ImageFileTest, WritePngRejectsInconsistentImage) {
  TempDir dir;
  Image broken{4, 4, std::vector<uint8_t>(10)};
  auto path = dir.path() / "broken.png";
  auto written = writePng(path, broken);
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().find(path.string()), std::string::npos) << written.error();
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ImageFileTest, WritePngIntoMissingDirectoryFails) {
  TempDir dir;
  auto path = dir.path() / "no" / "such" / "dir.png";
  auto written = writePng(path, makeSolid(2, kRed));
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().find(path.string()), std::string::npos) << written.error();
}

TEST(ImageFileTest, MissingFileErrorNamesPath) {
  TempDir dir;
  auto path = dir.path() / "missing.png";
  auto loaded = loadImage(path);
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().find(path.string()), std::string::npos) << loaded.error();
  EXPECT_NE(loaded.error().find("does not exist"), std::string::npos) << loaded.error();
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
  EXPECT_NE(loaded.error().find(path.string()), std::string::npos) << loaded.error();
}

}  // namespace
}  // namespace spire::scene

#include "scene/texture.h"

#include "common/png16.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <stb/stb_image_write.h>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace spire::scene {
namespace {

using testing::TempDir;

const Rgba8 kRed(255, 0, 0, 255);
const Rgba8 kBlue(0, 0, 255, 128);

TEST(TextureTest, CheckerExactPixels) {
  Image image = makeChecker(8, 4, kRed, kBlue);  // 2x2-pixel cells
  ASSERT_EQ(image.width, 8u);
  ASSERT_EQ(image.height, 8u);
  ASSERT_EQ(image.bytes.size(), 8u * 8u * 4u);
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
  EXPECT_EQ(makeNoise(64, 11, 5).bytes, image.bytes);
  EXPECT_NE(makeNoise(64, 12, 5).bytes, image.bytes);
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

// What a shader's specularGGXLut decodes from a texel's R and G.
double shaderDecodedGgx(const glm::vec4& texel) { return (texel.r * 65280.0 + texel.g * 255.0) / 65535.0; }

TEST(TextureTest, FloatGgxLutHoldsTheValueItselfInRAndG) {
  constexpr uint32_t kSize = 64;
  const Image split = makeGgxLut(kSize);
  for (PixelFormat format : {PixelFormat::RGBA32F, PixelFormat::RGBA16}) {
    const Image lut = makeGgxLut(kSize, format);
    ASSERT_EQ(lut.format, format);
    ASSERT_TRUE(lut.consistent());
    // Both round the double value to float, RGBA16 to 16 bits first.
    const double step = (format == PixelFormat::RGBA32F ? 0.0 : 0.5 / 65535.0) + 1e-7;
    for (uint32_t y = 0; y < kSize; ++y) {
      const double roughness = (y + 0.5) / kSize;
      const double alpha = std::max(roughness * roughness, static_cast<double>(kGgxMinAlpha));
      for (uint32_t x = 0; x < kSize; ++x) {
        const double sinTheta = (x + 0.5) / kSize;
        const double expected =
            ggxDistribution(std::sqrt(1.0 - sinTheta * sinTheta), alpha) / ggxDistribution(1.0, alpha);
        const glm::vec4 texel = lut.texel(x, y);
        EXPECT_NEAR(texel.r, expected, step) << x << "," << y;
        EXPECT_EQ(texel.g, texel.r) << x << "," << y;
        EXPECT_EQ(texel.b, 0.0F);
        EXPECT_EQ(texel.a, 1.0F);
        // The shader's split-byte decode reads the float table right too, and
        // agrees with the 8-bit table to its 16-bit step.
        EXPECT_NEAR(shaderDecodedGgx(texel), expected, step + 1e-6) << x << "," << y;
        EXPECT_NEAR(shaderDecodedGgx(texel), ggxLutValue(split, x, y), step + 0.5 / 65535.0) << x << "," << y;
      }
    }
  }
  // The tails of smooth surfaces: at roughness 0.1, 60 degrees off the
  // normal, D is 1.7e-8 of its peak, which 16 bits round to 0.
  EXPECT_NEAR(makeGgxLut(256, PixelFormat::RGBA32F).texel(221, 25).r, 1.7e-8, 0.05e-8);
  EXPECT_EQ(ggxLutValue(makeGgxLut(256), 221, 25), 0.0);
}

TEST(TextureTest, GgxLutInRgba8IsTheSplitTableWhetherAskedForOrNot) {
  EXPECT_EQ(makeGgxLut(32, PixelFormat::RGBA8).bytes, makeGgxLut(32).bytes);
}

TEST(TextureTest, FloatGeneratorsKeepWhatEightBitsRound) {
  const glm::vec4 color(0.123456F, 0.5F + 1.0F / 4096.0F, 1.0F / 3.0F, 0.75F);
  const Image solid = makeSolid(4, color, PixelFormat::RGBA32F);
  EXPECT_EQ(solid.texel(3, 2), color);
  const Image checker = makeChecker(4, 2, color, glm::vec4(0.0F), PixelFormat::RGBA16F);
  EXPECT_EQ(checker.texel(0, 0), glm::vec4(glm::unpackHalf4x16(glm::packHalf4x16(color))));
  EXPECT_EQ(checker.texel(2, 0), glm::vec4(0.0F));
  // Float noise is the 8-bit noise before rounding, and not all of it falls
  // on 8-bit steps.
  const Image grey = makeNoise(32, 7, 4);
  const Image fine = makeNoise(32, 7, 4, PixelFormat::RGBA32F);
  size_t between = 0;
  for (uint32_t y = 0; y < 32; ++y) {
    for (uint32_t x = 0; x < 32; ++x) {
      const float v = fine.texel(x, y).r;
      EXPECT_EQ(std::lround(v * 255.0F), grey.pixel(x, y).r) << x << "," << y;
      between += std::abs(v * 255.0F - std::round(v * 255.0F)) > 0.01F ? 1 : 0;
    }
  }
  EXPECT_GT(between, 500U);
  const Image normals = makeNormalMap(16, 5, 2.0F, PixelFormat::RGBA32F);
  for (uint32_t y = 0; y < 16; ++y) {
    for (uint32_t x = 0; x < 16; ++x) {
      EXPECT_NEAR(glm::length(glm::vec3(normals.texel(x, y)) * 2.0F - 1.0F), 1.0F, 1e-5F) << x << "," << y;
    }
  }
}

TEST(PixelFormatTest, EachFormatKeepsItsPrecision) {
  const auto roundTrip = [](PixelFormat format, const glm::vec4& value) {
    Image image = makeImage(1, 1, format);
    image.setTexel(0, 0, value);
    return image.texel(0, 0);
  };
  // Values 1/65535 apart stay apart in RGBA16 (and exact), not in RGBA8.
  const glm::vec4 a(1000.0F / 65535.0F, 1001.0F / 65535.0F, 0.0F, 1.0F);
  const glm::vec4 a16 = roundTrip(PixelFormat::RGBA16, a);
  EXPECT_EQ(std::lround(a16.r * 65535.0F), 1000);
  EXPECT_EQ(std::lround(a16.g * 65535.0F), 1001);
  const glm::vec4 a8 = roundTrip(PixelFormat::RGBA8, a);
  EXPECT_EQ(a8.r, a8.g);
  // Floats above 1 survive in float formats; unorm clamps them, and NaN to 0.
  const glm::vec4 bright(3.5F, 1000.125F, -2.0F, 1.0F);
  EXPECT_EQ(roundTrip(PixelFormat::RGBA32F, bright), bright);
  EXPECT_EQ(roundTrip(PixelFormat::RGBA16F, bright), glm::vec4(3.5F, 1000.0F, -2.0F, 1.0F));  // 11-bit mantissa
  EXPECT_EQ(roundTrip(PixelFormat::RGBA16, bright), glm::vec4(1.0F, 1.0F, 0.0F, 1.0F));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(roundTrip(PixelFormat::RGBA8, glm::vec4(nan, 0.5F, 2.0F, -1.0F)), glm::vec4(0.0F, 128 / 255.0F, 1, 0));
  // Half clamps finite values to its range instead of overflowing.
  EXPECT_EQ(roundTrip(PixelFormat::RGBA16F, glm::vec4(1e6F, -1e6F, 0, 1)), glm::vec4(65504.0F, -65504.0F, 0, 1));
  // R32F keeps red only and reads like a one-channel texture.
  EXPECT_EQ(roundTrip(PixelFormat::R32F, bright), glm::vec4(3.5F, 0.0F, 0.0F, 1.0F));
  EXPECT_EQ(texelBytes(PixelFormat::R32F), 4U);
  EXPECT_EQ(texelBytes(PixelFormat::RGBA16F), 8U);
}

TEST(PixelFormatTest, NamesAreTheSceneFilesAndTheBakeFormats) {
  for (const PixelFormatName& entry : kPixelFormats) {
    EXPECT_EQ(pixelFormatName(entry.format), entry.name);
    EXPECT_EQ(pixelFormatNamed(entry.name), entry.format);
  }
  EXPECT_EQ(pixelFormatNamed("RGBA16F"), PixelFormat::RGBA16F);
  EXPECT_FALSE(pixelFormatNamed("rgba16f"));
}

TEST(PixelFormatTest, WiderFormatHoldsBoth) {
  using enum PixelFormat;
  EXPECT_EQ(widerFormat(RGBA8, RGBA8), RGBA8);
  EXPECT_EQ(widerFormat(RGBA8, RGBA16), RGBA16);
  EXPECT_EQ(widerFormat(RGBA16, RGBA8), RGBA16);
  EXPECT_EQ(widerFormat(RGBA16F, RGBA16F), RGBA16F);
  EXPECT_EQ(widerFormat(RGBA8, RGBA16F), RGBA32F);
  EXPECT_EQ(widerFormat(RGBA16, RGBA16F), RGBA32F);
  EXPECT_EQ(widerFormat(R32F, R32F), RGBA32F);
  EXPECT_EQ(widerFormat(RGBA32F, RGBA8), RGBA32F);
}

TEST(PixelFormatTest, ConversionIsLosslessIntoWiderFormats) {
  const Image noise = makeNoise(17, 3, 4);
  for (PixelFormat wider : {PixelFormat::RGBA16, PixelFormat::RGBA32F}) {
    const Image converted = convertImage(noise, wider);
    ASSERT_EQ(converted.format, wider);
    ASSERT_TRUE(converted.consistent());
    EXPECT_EQ(convertImage(converted, PixelFormat::RGBA8).bytes, noise.bytes) << pixelFormatName(wider);
  }
  // An 8-bit value k is k * 257 in 16 bits.
  EXPECT_EQ(convertImage(makeSolid(1, Rgba8(1, 2, 255, 0)), PixelFormat::RGBA16).bytes,
            (std::vector<uint8_t>{1, 1, 2, 2, 255, 255, 0, 0}));
}

TEST(ImageFileTest, HdrKeepsValuesAboveOneAsRgba32F) {
  TempDir dir;
  // RGBE stores a shared exponent and 8-bit mantissas: these are exact in it.
  const std::vector<float> rgb = {3.5F, 0.25F, 1.0F, 100.0F, 64.0F, 32.0F, 0.0F, 0.0F, 0.0F, 0.5F, 0.5F, 0.5F};
  const auto path = dir.path() / "bright.hdr";
  ASSERT_NE(stbi_write_hdr(path.c_str(), 2, 2, 3, rgb.data()), 0);
  auto loaded = loadImage(path);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->format, PixelFormat::RGBA32F);
  ASSERT_TRUE(loaded->consistent());
  EXPECT_EQ(loaded->texel(0, 0), glm::vec4(3.5F, 0.25F, 1.0F, 1.0F));
  EXPECT_EQ(loaded->texel(1, 0), glm::vec4(100.0F, 64.0F, 32.0F, 1.0F));
  EXPECT_EQ(loaded->texel(1, 1), glm::vec4(0.5F, 0.5F, 0.5F, 1.0F));
  // Asked for as RGBA8 it clamps, as documented.
  EXPECT_EQ(convertImage(*loaded, PixelFormat::RGBA8).pixel(1, 0), Rgba8(255, 255, 255, 255));
}

TEST(ImageFileTest, SixteenBitPngKeepsEverySixteenBitValueAsRgba16) {
  TempDir dir;
  // Neighbours one 16-bit step apart, which 8 bits would merge.
  const std::vector<uint16_t> rgba = {1000, 1001, 65535, 0, 1, 2, 3, 65534, 40000, 40001, 40002, 40003};
  const auto path = dir.path() / "fine.png";
  {
    std::ofstream out(path, std::ios::binary);
    out << spire::testing_util::encodePng16(3, 1, rgba);
  }
  auto loaded = loadImage(path);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->format, PixelFormat::RGBA16);
  ASSERT_EQ(loaded->width, 3U);
  ASSERT_TRUE(loaded->consistent());
  for (uint32_t x = 0; x < 3; ++x) {
    const glm::vec4 texel = loaded->texel(x, 0);
    for (glm::length_t c = 0; c < 4; ++c) {
      EXPECT_EQ(std::lround(texel[c] * 65535.0F), rgba[x * 4 + static_cast<size_t>(c)]) << x << "," << c;
    }
  }
  EXPECT_NE(loaded->texel(0, 0).r, loaded->texel(0, 0).g);
  // PNG output stays 8-bit: a 16-bit image is an error, not a silent cut.
  auto encoded = encodePng(*loaded);
  ASSERT_FALSE(encoded);
  EXPECT_NE(encoded.error().message.find("RGBA16"), std::string::npos) << encoded.error().message;
}

TEST(ImageFileTest, PngRoundTripIsBitExact) {
  TempDir dir;
  Image original = makeNoise(33, 3, 4);  // odd size catches stride mistakes
  original.bytes[3] = 7;                 // non-opaque alpha must survive too
  auto path = dir.path() / "noise.png";
  auto written = writePng(path, original);
  ASSERT_TRUE(written) << written.error().message;
  auto loaded = loadImage(path);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->width, 33u);
  EXPECT_EQ(loaded->height, 33u);
  EXPECT_EQ(loaded->bytes, original.bytes);
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
  ASSERT_NE(stbi_write_jpg(path.c_str(), 16, 16, 4, solid.bytes.data(), 100), 0);
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

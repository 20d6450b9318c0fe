#include "measure/comparison_image.h"

#include "measure/bitmap_font.h"

#include <gtest/gtest.h>

namespace spire::measure {
namespace {

using scene::Image;
using scene::Rgba8;

const Rgba8 kBackground(24, 24, 24, 255);
const Rgba8 kStrip(48, 48, 48, 255);
const Rgba8 kText(240, 240, 240, 255);

Image solid(uint32_t width, uint32_t height, Rgba8 color) {
  Image image{width, height, {}};
  for (uint32_t p = 0; p < width * height; ++p)
    image.bytes.insert(image.bytes.end(), {color.r, color.g, color.b, color.a});
  return image;
}

Image compose(const std::vector<Panel>& panels, ComparisonLayout layout = {.gap = 4, .textScale = 1}) {
  auto image = makeComparisonImage(panels, layout);
  EXPECT_TRUE(image) << image.error().message;
  return image ? *image : Image{};
}

// Scale 1: the strip is 7 + 2 * 2 pixels high; text starts 2 pixels in.
constexpr uint32_t kGap = 4;
constexpr uint32_t kPadding = 2;
constexpr uint32_t kStripHeight = 11;

TEST(ComparisonImageTest, PanelsSideBySideWithCaptionStrips) {
  Image red = solid(10, 6, Rgba8(255, 0, 0, 128));  // alpha is not kept
  Image blue = solid(8, 4, Rgba8(0, 0, 255, 255));
  Image out = compose({{red, "REF"}, {blue, "X"}});
  ASSERT_EQ(out.width, kGap + 10 + kGap + 8 + kGap);
  ASSERT_EQ(out.height, kGap + 6 + kStripHeight + kGap);
  EXPECT_EQ(out.pixel(0, 0), kBackground);
  EXPECT_EQ(out.pixel(kGap, kGap), Rgba8(255, 0, 0, 255));
  EXPECT_EQ(out.pixel(kGap + 9, kGap + 5), Rgba8(255, 0, 0, 255));
  uint32_t blueLeft = kGap + 10 + kGap;
  EXPECT_EQ(out.pixel(blueLeft, kGap), Rgba8(0, 0, 255, 255));
  EXPECT_EQ(out.pixel(blueLeft, kGap + 4), kBackground) << "below the shorter image";
  // Both strips start below the tallest image.
  uint32_t stripTop = kGap + 6;
  EXPECT_EQ(out.pixel(kGap, stripTop), kStrip);
  EXPECT_EQ(out.pixel(blueLeft + 7, stripTop + kStripHeight - 1), kStrip);
  EXPECT_EQ(out.pixel(kGap + 10, stripTop), kBackground) << "gap between strips";
}

TEST(ComparisonImageTest, CaptionGlyphsLandWhereExpected) {
  Image panel = solid(20, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "I-"}});
  uint32_t left = kGap + kPadding;
  uint32_t top = kGap + 2 + kPadding;
  // 'I' is ".###." on its top row and "..#.." below.
  EXPECT_EQ(out.pixel(left, top), kStrip);
  for (uint32_t x = 1; x <= 3; ++x) EXPECT_EQ(out.pixel(left + x, top), kText) << x;
  EXPECT_EQ(out.pixel(left + 4, top), kStrip);
  EXPECT_EQ(out.pixel(left + 2, top + 3), kText);
  EXPECT_EQ(out.pixel(left + 1, top + 3), kStrip);
  // '-' follows one advance later, on the middle row.
  EXPECT_EQ(out.pixel(left + kGlyphAdvance + 2, top + 3), kText);
  EXPECT_EQ(out.pixel(left + kGlyphAdvance + 2, top), kStrip);
}

TEST(ComparisonImageTest, CaptionStripHasTextInEveryPanel) {
  Image a = solid(60, 8, Rgba8(10, 10, 10, 255));
  Image out = compose({{a, "BAKED_ALBEDO 2.41X"}, {a, "RMSE 0.031 (=5%)"}});
  for (uint32_t left : {kGap, kGap + 60 + kGap}) {
    size_t ink = 0;
    for (uint32_t y = kGap + 8; y < kGap + 8 + kStripHeight; ++y) {
      for (uint32_t x = left; x < left + 60; ++x) ink += out.pixel(x, y) == kText ? 1 : 0;
    }
    EXPECT_GT(ink, 40u) << "panel at " << left;
  }
}

TEST(ComparisonImageTest, LowercaseIsUppercaseAndUnknownIsABox) {
  Image panel = solid(40, 2, Rgba8(0, 0, 0, 255));
  EXPECT_EQ(compose({{panel, "rmse 1.5x"}}).bytes, compose({{panel, "RMSE 1.5X"}}).bytes);
  Image unknown = compose({{panel, "#"}});
  EXPECT_NE(unknown.bytes, compose({{panel, " "}}).bytes);
  EXPECT_EQ(unknown.pixel(kGap + kPadding, kGap + 2 + kPadding), kText);
}

TEST(ComparisonImageTest, LongCaptionIsCutAtThePanelEdge) {
  Image panel = solid(16, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "WWWWWWWWWWWWWWWWWWWW"}});
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = kGap + 16; x < out.width; ++x) EXPECT_EQ(out.pixel(x, y), kBackground) << x << "," << y;
  }
}

TEST(ComparisonImageTest, WideCaptionIsDrawnSmallerFirst) {
  // Six glyphs need 70 pixels at scale 2 but 35 at scale 1; 44 - 2 * 4 are free.
  Image panel = solid(44, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "IIIIII"}}, {.gap = 4, .textScale = 2});
  uint32_t left = 4 + 4;
  uint32_t top = 4 + 2 + (22 - 7) / 2;  // centred in the scale-2 strip
  for (uint32_t glyph = 0; glyph < 6; ++glyph) {
    EXPECT_EQ(out.pixel(left + glyph * kGlyphAdvance + 1, top), kText) << glyph;
    EXPECT_EQ(out.pixel(left + glyph * kGlyphAdvance, top), kStrip) << glyph;
  }
}

// A caption too wide for scale 2 in one panel sets the size of all: the
// short caption beside it is drawn at scale 1 too.
TEST(ComparisonImageTest, EveryCaptionHasTheSizeOfTheSmallest) {
  Image panel = solid(44, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "I"}, {panel, "IIIIII"}}, {.gap = 4, .textScale = 2});
  const auto inkRows = [&](uint32_t left) {
    uint32_t rows = 0;
    for (uint32_t y = 0; y < out.height; ++y) {
      bool ink = false;
      for (uint32_t x = left; x < left + 44; ++x) ink = ink || out.pixel(x, y) == kText;
      rows += ink ? 1 : 0;
    }
    return rows;
  };
  EXPECT_EQ(inkRows(4), 7u) << "the short caption is drawn at scale 1";
  EXPECT_EQ(inkRows(4 + 44 + 4), 7u);
}

TEST(ComparisonImageTest, ScaleEnlargesTheText) {
  EXPECT_EQ(textWidth("AB", 1), 11u);
  EXPECT_EQ(textWidth("AB", 3), 33u);
  EXPECT_EQ(textWidth("", 2), 0u);
  Image panel = solid(40, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "I"}}, {.gap = 4, .textScale = 2});
  EXPECT_EQ(out.height, 4 + 2 + (7 * 2 + 2 * 4) + 4u);
  uint32_t left = 4 + 4;
  uint32_t top = 4 + 2 + 4;
  // The top row's middle '#' of 'I' (column 2) is a 2x2 block.
  for (uint32_t dy = 0; dy < 2; ++dy) {
    for (uint32_t dx = 0; dx < 2; ++dx) EXPECT_EQ(out.pixel(left + 4 + dx, top + dy), kText);
  }
  EXPECT_EQ(out.pixel(left + 1, top), kStrip);
}

TEST(ComparisonImageTest, BadInputsAreErrors) {
  EXPECT_FALSE(makeComparisonImage({}));
  Image broken{4, 4, std::vector<uint8_t>(5)};
  auto inconsistent = makeComparisonImage({{broken, "BROKEN"}});
  ASSERT_FALSE(inconsistent);
  EXPECT_NE(inconsistent.error().message.find("BROKEN"), std::string::npos) << inconsistent.error().message;
  Image tall{1, 70000, std::vector<uint8_t>(70000 * 4)};
  EXPECT_FALSE(makeComparisonImage({{tall, "TALL"}}));
}

}  // namespace
}  // namespace spire::measure

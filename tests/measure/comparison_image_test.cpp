#include "measure/comparison_image.h"

#include "measure/caption_text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>

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

// Scale 1: the strip is a line of text plus 2 * 2 pixels high; text starts
// 2 pixels in.
constexpr uint32_t kGap = 4;
constexpr uint32_t kPadding = 2;
const uint32_t kStripHeight = textHeight(1) + 2 * kPadding;

// Rows and columns of `image` holding text pixels, within [left, right).
struct Ink {
  uint32_t pixels = 0;
  uint32_t top = UINT32_MAX, bottom = 0, left = UINT32_MAX, right = 0;  // bottom, right exclusive
};
Ink inkOf(const Image& image, uint32_t from, uint32_t to) {
  Ink ink;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = from; x < to && x < image.width; ++x) {
      if (image.pixel(x, y) != kText) continue;
      ++ink.pixels;
      ink.top = std::min(ink.top, y);
      ink.bottom = std::max(ink.bottom, y + 1);
      ink.left = std::min(ink.left, x);
      ink.right = std::max(ink.right, x + 1);
    }
  }
  return ink;
}

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

// The caption's pixels lie in its line's box, from the padding on.
TEST(ComparisonImageTest, CaptionTextLandsInItsBox) {
  Image panel = solid(40, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "I-"}});
  const uint32_t left = kGap + kPadding;
  const uint32_t top = kGap + 2 + kPadding;
  const Ink ink = inkOf(out, 0, out.width);
  ASSERT_GT(ink.pixels, 4u);
  EXPECT_GE(ink.left, left);
  EXPECT_LE(ink.right, left + textWidth("I-", 1));
  EXPECT_GE(ink.top, top);
  EXPECT_LE(ink.bottom, top + textHeight(1));
}

TEST(ComparisonImageTest, CaptionStripHasTextInEveryPanel) {
  Image a = solid(60, 8, Rgba8(10, 10, 10, 255));
  Image out = compose({{a, "BAKED_ALBEDO 2.41X"}, {a, "RMSE 0.031 (=5%)"}});
  for (uint32_t left : {kGap, kGap + 60 + kGap}) {
    EXPECT_GT(inkOf(out, left, left + 60).pixels, 40u) << "panel at " << left;
  }
}

// stb_easy_font knows printable ASCII only: anything else is a '?', never
// an out-of-range read.
TEST(ComparisonImageTest, BytesOutsidePrintableAsciiAreQuestionMarks) {
  Image panel = solid(40, 2, Rgba8(0, 0, 0, 255));
  EXPECT_EQ(compose({{panel, "\xc3\xa9\x01"}}).bytes, compose({{panel, "???"}}).bytes);
  EXPECT_NE(compose({{panel, "rmse"}}).bytes, compose({{panel, "RMSE"}}).bytes);
}

TEST(ComparisonImageTest, LongCaptionIsCutAtThePanelEdge) {
  Image panel = solid(16, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "WWWWWWWWWWWWWWWWWWWW"}});
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = kGap + 16; x < out.width; ++x) EXPECT_EQ(out.pixel(x, y), kBackground) << x << "," << y;
  }
}

// A panel whose caption fits at scale 1 but not at 2: drawn at 1, in a
// strip sized for 2.
TEST(ComparisonImageTest, WideCaptionIsDrawnSmallerFirst) {
  const std::string caption = "IIIIII";
  const uint32_t width = textWidth(caption, 1) + 2 * 4 + 1;
  ASSERT_GT(textWidth(caption, 2), width - 2 * 4);
  Image panel = solid(width, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, caption}}, {.gap = 4, .textScale = 2});
  EXPECT_EQ(out.height, 4 + 2 + (textHeight(2) + 2 * 4) + 4u);
  const Ink small = inkOf(compose({{panel, caption}}), 0, out.width);
  const Ink ink = inkOf(out, 0, out.width);
  EXPECT_EQ(ink.pixels, small.pixels);
  EXPECT_EQ(ink.bottom - ink.top, small.bottom - small.top);
}

// A caption too wide for scale 2 in one panel sets the size of all: the
// short caption beside it is drawn at scale 1 too.
TEST(ComparisonImageTest, EveryCaptionHasTheSizeOfTheSmallest) {
  const std::string wide = "IIIIII";
  const uint32_t width = textWidth(wide, 1) + 2 * 4 + 1;
  Image panel = solid(width, 2, Rgba8(0, 0, 0, 255));
  Image out = compose({{panel, "I"}, {panel, wide}}, {.gap = 4, .textScale = 2});
  const Ink alone = inkOf(compose({{panel, "I"}}, {.gap = 4, .textScale = 1}), 0, width + 8);
  const Ink beside = inkOf(out, 4, 4 + width);
  EXPECT_EQ(beside.pixels, alone.pixels) << "the short caption is drawn at scale 1";
}

TEST(ComparisonImageTest, ScaleEnlargesTheText) {
  EXPECT_EQ(textWidth("AB", 3), 3 * textWidth("AB", 1));
  EXPECT_GT(textWidth("AB", 1), 0u);
  EXPECT_EQ(textWidth("", 2), 0u);
  EXPECT_EQ(textHeight(2), 2 * textHeight(1));
  Image panel = solid(60, 2, Rgba8(0, 0, 0, 255));
  const Ink one = inkOf(compose({{panel, "IT"}}, {.gap = 4, .textScale = 1}), 0, 80);
  const Ink two = inkOf(compose({{panel, "IT"}}, {.gap = 4, .textScale = 2}), 0, 80);
  EXPECT_EQ(two.pixels, 4 * one.pixels);
  EXPECT_EQ(two.bottom - two.top, 2 * (one.bottom - one.top));
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

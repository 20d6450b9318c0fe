#include "measure/comparison_image.h"

#include "measure/caption_text.h"

#include <fmt/format.h>

#include <algorithm>

namespace spire::measure {
namespace {

constexpr scene::Rgba8 kBackground{24, 24, 24, 255};
constexpr scene::Rgba8 kStrip{48, 48, 48, 255};
constexpr scene::Rgba8 kText{240, 240, 240, 255};
// Far beyond any report, yet small enough that the canvas size cannot overflow.
constexpr uint64_t kMaxSide = 65535;

void fillRect(scene::Image& image, uint32_t x, uint32_t y, uint32_t width, uint32_t height, scene::Rgba8 color) {
  for (uint32_t py = y; py < y + height; ++py) {
    for (uint32_t px = x; px < x + width; ++px) {
      size_t offset = (static_cast<size_t>(py) * image.width + px) * 4;
      for (int c = 0; c < 4; ++c) image.bytes[offset + static_cast<size_t>(c)] = color[c];
    }
  }
}

void blitOpaque(scene::Image& canvas, const scene::Image& image, uint32_t x, uint32_t y) {
  for (uint32_t row = 0; row < image.height; ++row) {
    for (uint32_t column = 0; column < image.width; ++column) {
      size_t from = (static_cast<size_t>(row) * image.width + column) * 4;
      size_t to = (static_cast<size_t>(y + row) * canvas.width + x + column) * 4;
      std::copy_n(&image.bytes[from], 3, &canvas.bytes[to]);
      canvas.bytes[to + 3] = 255;
    }
  }
}

// The longest prefix of `caption` that fits in `width` pixels.
std::string_view fitCaption(std::string_view caption, uint32_t width, uint32_t scale) {
  while (!caption.empty() && textWidth(caption, scale) > width) caption.remove_suffix(1);
  return caption;
}

}  // namespace

scene::Expected<scene::Image> makeComparisonImage(const std::vector<Panel>& panels, const ComparisonLayout& layout) {
  if (panels.empty()) return scene::Error{"cannot make a comparison image of no images"};
  uint32_t scale = std::max(layout.textScale, 1u);
  uint64_t padding = uint64_t{scale} * 2;
  uint64_t stripHeight = uint64_t{textHeight(scale)} + 2 * padding;
  uint64_t width = layout.gap;
  uint64_t tallest = 0;
  for (size_t i = 0; i < panels.size(); ++i) {
    const scene::Image& image = panels[i].image;
    if (image.format != scene::PixelFormat::RGBA8 || !image.consistent()) {
      return scene::Error{
          fmt::format("cannot make a comparison image: image {} ('{}') has pixel data that does "
                      "not match {}x{} RGBA8",
                      i, panels[i].caption, image.width, image.height)};
    }
    width += uint64_t{image.width} + layout.gap;
    tallest = std::max<uint64_t>(tallest, image.height);
  }
  uint64_t height = uint64_t{layout.gap} + tallest + stripHeight + layout.gap;
  if (width > kMaxSide || height > kMaxSide) {
    return scene::Error{
        fmt::format("cannot make a comparison image: {}x{} is larger than {} pixels a side", width, height, kMaxSide)};
  }

  scene::Image canvas;
  canvas.width = static_cast<uint32_t>(width);
  canvas.height = static_cast<uint32_t>(height);
  canvas.bytes.resize(static_cast<size_t>(width) * height * 4);
  fillRect(canvas, 0, 0, canvas.width, canvas.height, kBackground);
  auto stripTop = static_cast<uint32_t>(layout.gap + tallest);
  const auto textSpaceOf = [&](const Panel& panel) {
    return static_cast<uint32_t>(panel.image.width > 2 * padding ? panel.image.width - 2 * padding : 0);
  };
  // One text size for every caption, the largest at which all fit, so that
  // captions read as a row rather than as a short one shouting.
  uint32_t captionScale = scale;
  for (const Panel& panel : panels) {
    while (captionScale > 1 && textWidth(panel.caption, captionScale) > textSpaceOf(panel)) --captionScale;
  }
  uint32_t left = layout.gap;
  for (const Panel& panel : panels) {
    blitOpaque(canvas, panel.image, left, layout.gap);
    fillRect(canvas, left, stripTop, panel.image.width, static_cast<uint32_t>(stripHeight), kStrip);
    const uint32_t textSpace = textSpaceOf(panel);
    uint64_t textTop = stripTop + (stripHeight - uint64_t{textHeight(captionScale)}) / 2;
    drawText(canvas, left + static_cast<uint32_t>(padding), static_cast<uint32_t>(textTop),
             fitCaption(panel.caption, textSpace, captionScale), captionScale, kText);
    left += panel.image.width + layout.gap;
  }
  return canvas;
}

}  // namespace spire::measure

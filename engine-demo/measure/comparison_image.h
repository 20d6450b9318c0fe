#pragma once

// Side-by-side comparison image of several renderings, each captioned on a
// dark strip below it (e.g. "BAKED_ALBEDO 2.41X RMSE 0.031"), written by the
// demo next to its report so a variant's error can be seen, not just read.

#include "scene/expected.h"
#include "scene/texture.h"

#include <cstdint>
#include <string>
#include <vector>

namespace spire::measure {

struct Panel {
  const scene::Image& image;
  // Drawn with stb_easy_font (caption_text.h). A caption too wide for its
  // panel is drawn smaller, down to scale 1, and only then cut off.
  std::string caption;
};

struct ComparisonLayout {
  uint32_t gap = 8;        // pixels between panels and around the whole image
  uint32_t textScale = 2;  // each font pixel drawn as textScale x textScale
};

// Panels left to right, tops aligned, captions on one line below the tallest
// image. The result is opaque: the panels' alpha is not kept, so a rendering
// with alpha < 1 still shows its colors. No panels, an image whose pixel
// array does not match its size, or a result wider or taller than 65535
// pixels give an error.
scene::Expected<scene::Image> makeComparisonImage(const std::vector<Panel>& panels,
                                                  const ComparisonLayout& layout = {});

}  // namespace spire::measure

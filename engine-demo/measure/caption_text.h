// Text in result images (captions of comparison images, axis labels of the
// tuner's plot), drawn with stb_easy_font from Debian's libstb-dev, so that
// writing a PNG report needs no font files and no font of our own. It has
// printable ASCII; any other byte is drawn as '?'.
#pragma once

#include <cstdint>
#include <string_view>

#include "scene/texture.h"

namespace spire::measure {

// Width in pixels of `text` drawn at `scale` (each font pixel a scale x
// scale block).
uint32_t textWidth(std::string_view text, uint32_t scale);

// Height in pixels of a line at `scale`, from the top of the tallest glyph
// to the bottom of the lowest descender: what a caption strip must hold.
uint32_t textHeight(uint32_t scale);

// Draws `text` with the top-left corner of its line at (x, y); pixels that
// fall outside the image are skipped.
void drawText(scene::Image& image, uint32_t x, uint32_t y, std::string_view text, uint32_t scale, scene::Rgba8 color);

}  // namespace spire::measure

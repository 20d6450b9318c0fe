#pragma once

// A tiny built-in 5x7 bitmap font for captions in result images, so that
// writing a PNG report needs no font files or font library. It covers
// uppercase letters, digits, space and . : % - _ / ( ) =; lowercase letters
// are drawn as uppercase and any other character as a hollow box.

#include "scene/texture.h"

#include <cstdint>
#include <string_view>

namespace spire::measure {

inline constexpr uint32_t kGlyphWidth = 5;
inline constexpr uint32_t kGlyphHeight = 7;
inline constexpr uint32_t kGlyphAdvance = kGlyphWidth + 1;  // one column of spacing

// Width in pixels of `text` drawn at `scale` (each font pixel a scale x scale
// block), without the spacing after the last character.
uint32_t textWidth(std::string_view text, uint32_t scale);

// Draws `text` with its top-left corner at (x, y); pixels falling outside the
// image are skipped.
void drawText(scene::Image& image, uint32_t x, uint32_t y, std::string_view text, uint32_t scale, scene::Rgba8 color);

}  // namespace spire::measure

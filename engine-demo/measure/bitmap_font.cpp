#include "measure/bitmap_font.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>

namespace spire::measure {
namespace {

// Each glyph is drawn as seven rows of five columns, top row first, separated
// by spaces; '#' is ink.
struct Glyph {
  char character;
  std::string_view rows;
};

// clang-format off
constexpr std::array kGlyphs = {
    Glyph{'A', ".###. #...# #...# ##### #...# #...# #...#"},
    Glyph{'B', "####. #...# #...# ####. #...# #...# ####."},
    Glyph{'C', ".###. #...# #.... #.... #.... #...# .###."},
    Glyph{'D', "####. #...# #...# #...# #...# #...# ####."},
    Glyph{'E', "##### #.... #.... ####. #.... #.... #####"},
    Glyph{'F', "##### #.... #.... ####. #.... #.... #...."},
    Glyph{'G', ".###. #...# #.... #.### #...# #...# .####"},
    Glyph{'H', "#...# #...# #...# ##### #...# #...# #...#"},
    Glyph{'I', ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###."},
    Glyph{'J', "..### ...#. ...#. ...#. ...#. #..#. .##.."},
    Glyph{'K', "#...# #..#. #.#.. ##... #.#.. #..#. #...#"},
    Glyph{'L', "#.... #.... #.... #.... #.... #.... #####"},
    Glyph{'M', "#...# ##.## #.#.# #.#.# #...# #...# #...#"},
    Glyph{'N', "#...# #...# ##..# #.#.# #..## #...# #...#"},
    Glyph{'O', ".###. #...# #...# #...# #...# #...# .###."},
    Glyph{'P', "####. #...# #...# ####. #.... #.... #...."},
    Glyph{'Q', ".###. #...# #...# #...# #.#.# #..#. .##.#"},
    Glyph{'R', "####. #...# #...# ####. #.#.. #..#. #...#"},
    Glyph{'S', ".#### #.... #.... .###. ....# ....# ####."},
    Glyph{'T', "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#.."},
    Glyph{'U', "#...# #...# #...# #...# #...# #...# .###."},
    Glyph{'V', "#...# #...# #...# #...# #...# .#.#. ..#.."},
    Glyph{'W', "#...# #...# #...# #.#.# #.#.# #.#.# .#.#."},
    Glyph{'X', "#...# #...# .#.#. ..#.. .#.#. #...# #...#"},
    Glyph{'Y', "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#.."},
    Glyph{'Z', "##### ....# ...#. ..#.. .#... #.... #####"},
    Glyph{'0', ".###. #...# #..## #.#.# ##..# #...# .###."},
    Glyph{'1', "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###."},
    Glyph{'2', ".###. #...# ....# ...#. ..#.. .#... #####"},
    Glyph{'3', "##### ...#. ..#.. ...#. ....# #...# .###."},
    Glyph{'4', "...#. ..##. .#.#. #..#. ##### ...#. ...#."},
    Glyph{'5', "##### #.... ####. ....# ....# #...# .###."},
    Glyph{'6', "..##. .#... #.... ####. #...# #...# .###."},
    Glyph{'7', "##### ....# ...#. ..#.. .#... .#... .#..."},
    Glyph{'8', ".###. #...# #...# .###. #...# #...# .###."},
    Glyph{'9', ".###. #...# #...# .#### ....# ...#. .##.."},
    Glyph{' ', "..... ..... ..... ..... ..... ..... ....."},
    Glyph{'.', "..... ..... ..... ..... ..... .##.. .##.."},
    Glyph{':', "..... .##.. .##.. ..... .##.. .##.. ....."},
    Glyph{'%', "##... ##..# ...#. ..#.. .#... #..## ...##"},
    Glyph{'-', "..... ..... ..... .###. ..... ..... ....."},
    Glyph{'_', "..... ..... ..... ..... ..... ..... #####"},
    Glyph{'/', "..... ....# ...#. ..#.. .#... #.... ....."},
    Glyph{'(', "...#. ..#.. .#... .#... .#... ..#.. ...#."},
    Glyph{')', ".#... ..#.. ...#. ...#. ...#. ..#.. .#..."},
    Glyph{'=', "..... ..... ##### ..... ##### ..... ....."},
};
// clang-format on
static_assert(std::all_of(kGlyphs.begin(), kGlyphs.end(), [](const Glyph& glyph) {
  return glyph.rows.size() == kGlyphHeight * (kGlyphWidth + 1) - 1;
}));

constexpr std::string_view kUnknownGlyph = "##### #...# #...# #...# #...# #...# #####";

std::string_view glyphRows(char character) {
  char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(character)));
  for (const Glyph& glyph : kGlyphs) {
    if (glyph.character == upper) return glyph.rows;
  }
  return kUnknownGlyph;
}

void fillBlock(scene::Image& image, uint64_t x, uint64_t y, uint32_t scale, scene::Rgba8 color) {
  for (uint64_t py = y; py < y + scale && py < image.height; ++py) {
    for (uint64_t px = x; px < x + scale && px < image.width; ++px) {
      size_t offset = (static_cast<size_t>(py) * image.width + static_cast<size_t>(px)) * 4;
      for (int c = 0; c < 4; ++c) image.bytes[offset + static_cast<size_t>(c)] = color[c];
    }
  }
}

}  // namespace

uint32_t textWidth(std::string_view text, uint32_t scale) {
  if (text.empty()) return 0;
  uint64_t width = (uint64_t{text.size()} * kGlyphAdvance - 1) * scale;
  return static_cast<uint32_t>(std::min<uint64_t>(width, UINT32_MAX));
}

void drawText(scene::Image& image, uint32_t x, uint32_t y, std::string_view text, uint32_t scale, scene::Rgba8 color) {
  if (image.format != scene::PixelFormat::RGBA8 || !image.consistent()) return;
  // 64-bit positions: a long caption at a large scale must clip, not wrap around.
  uint64_t left = x;
  for (char character : text) {
    if (left >= image.width) break;
    std::string_view rows = glyphRows(character);
    for (uint32_t row = 0; row < kGlyphHeight; ++row) {
      for (uint32_t column = 0; column < kGlyphWidth; ++column) {
        if (rows[row * (kGlyphWidth + 1) + column] != '#') continue;
        fillBlock(image, left + uint64_t{column} * scale, uint64_t{y} + uint64_t{row} * scale, scale, color);
      }
    }
    left += uint64_t{kGlyphAdvance} * scale;
  }
}

}  // namespace spire::measure

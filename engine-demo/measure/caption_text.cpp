#include "measure/caption_text.h"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace spire::measure {
namespace {

// stb_easy_font indexes its tables by character - 32 and knows 32..126.
std::string printable(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c < 32 || c > 126) c = '?';
  }
  return out;
}

// stb_easy_font's vertex: position, an unused z, and a color.
struct FontVertex {
  float x, y, z;
  unsigned char color[4];
};

// The quads of `text` at the origin, in font pixels.
std::vector<FontVertex> quadsOf(std::string_view text) {
  std::string line = printable(text);
  // stb_easy_font's documented average is 270 bytes a character.
  std::vector<FontVertex> vertices((line.size() + 1) * 64);
  const int quads = stb_easy_font_print(0.0F, 0.0F, line.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size() * sizeof(FontVertex)));
  vertices.resize(static_cast<size_t>(std::max(quads, 0)) * 4);
  return vertices;
}

void fillRect(scene::Image& image, int64_t x0, int64_t y0, int64_t x1, int64_t y1, scene::Rgba8 color) {
  x0 = std::max<int64_t>(x0, 0);
  y0 = std::max<int64_t>(y0, 0);
  x1 = std::min<int64_t>(x1, image.width);
  y1 = std::min<int64_t>(y1, image.height);
  for (int64_t y = y0; y < y1; ++y) {
    for (int64_t x = x0; x < x1; ++x) {
      const size_t offset = (static_cast<size_t>(y) * image.width + static_cast<size_t>(x)) * 4;
      for (size_t c = 0; c < 4; ++c) image.bytes[offset + c] = color[static_cast<int>(c)];
    }
  }
}

}  // namespace

uint32_t textWidth(std::string_view text, uint32_t scale) {
  if (text.empty()) return 0;
  std::string line = printable(text);
  return static_cast<uint32_t>(stb_easy_font_width(line.data())) * scale;
}

uint32_t textHeight(uint32_t scale) {
  static const uint32_t kHeight = [] {
    std::string all;
    for (char c = 32; c < 127; ++c) all += c;
    float bottom = 0.0F;
    for (const FontVertex& v : quadsOf(all)) bottom = std::max(bottom, v.y);
    return static_cast<uint32_t>(std::ceil(bottom));
  }();
  return kHeight * scale;
}

void drawText(scene::Image& image, uint32_t x, uint32_t y, std::string_view text, uint32_t scale, scene::Rgba8 color) {
  if (image.format != scene::PixelFormat::RGBA8 || !image.consistent()) return;
  const std::vector<FontVertex> vertices = quadsOf(text);
  const auto at = [&](float v, uint32_t origin) {
    return int64_t{origin} + static_cast<int64_t>(std::lround(v * static_cast<float>(scale)));
  };
  // Each quad is an axis-aligned rectangle: its first and third corners
  // are opposite.
  for (size_t q = 0; q + 3 < vertices.size(); q += 4) {
    const FontVertex& a = vertices[q];
    const FontVertex& c = vertices[q + 2];
    fillRect(image, at(std::min(a.x, c.x), x), at(std::min(a.y, c.y), y), at(std::max(a.x, c.x), x),
             at(std::max(a.y, c.y), y), color);
  }
}

}  // namespace spire::measure

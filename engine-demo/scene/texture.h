#pragma once

// Images of one PixelFormat: procedural generators for the demo's materials,
// and image file I/O (PNG, JPEG, Radiance .hdr). Rows are stored top to
// bottom. The generators make RGBA8 by default, byte for byte what they made
// before other formats existed; asked for another format they compute at
// float precision and write that format's texels directly.

#include "scene/expected.h"
#include "scene/pixel_format.h"

#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace spire::scene {

using Rgba8 = glm::u8vec4;

struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> bytes;  // width * height texels of texelBytes(format) bytes
  PixelFormat format = PixelFormat::RGBA8;

  // The texel of an RGBA8 image.
  [[nodiscard]] Rgba8 pixel(uint32_t x, uint32_t y) const;
  // The texel of an image of any format, as decodeTexel reads it.
  [[nodiscard]] glm::vec4 texel(uint32_t x, uint32_t y) const;
  // Writes a texel as encodeTexel does (rounding, clamping to the format).
  void setTexel(uint32_t x, uint32_t y, const glm::vec4& value);
  // Whether `bytes` holds exactly width x height texels of `format`.
  [[nodiscard]] bool consistent() const;
};

// width x height texels of `format`, all bytes 0.
Image makeImage(uint32_t width, uint32_t height, PixelFormat format);

// `image` in `format`, texel by texel as Image::texel reads it and
// Image::setTexel writes it: lossless into a wider format (widerFormat),
// rounded and clamped into a narrower one (an .hdr image into RGBA8 clamps to
// [0, 1]; R32F keeps red only).
Image convertImage(Image image, PixelFormat format);

// size x size checkerboard of cells x cells squares; the top-left is colorA.
Image makeChecker(uint32_t size, uint32_t cells, Rgba8 colorA, Rgba8 colorB);
Image makeChecker(uint32_t size, uint32_t cells, const glm::vec4& colorA, const glm::vec4& colorB, PixelFormat format);

// Grey fBm noise in [0, 1] (opaque); a given seed gives identical bytes
// everywhere.
Image makeNoise(uint32_t size, uint32_t seed, uint32_t octaves, PixelFormat format = PixelFormat::RGBA8);

// Tangent-space normal map of a noise heightfield, RGB = n * 0.5 + 0.5.
// +X follows increasing u (image x), +Y increasing v (image rows), matching the
// tangent/bitangent of computeTangents; `strength` scales the slopes.
Image makeNormalMap(uint32_t size, uint32_t seed, float strength, PixelFormat format = PixelFormat::RGBA8);

Image makeSolid(uint32_t size, Rgba8 color);
Image makeSolid(uint32_t size, const glm::vec4& color, PixelFormat format);

// The alpha below which GGX tables and shaders clamp: alpha = 0 would be a
// delta lobe. stdlib/pbr.spire's ggxAlpha uses the same floor.
constexpr float kGgxMinAlpha = 2e-3F;

// Lookup table of the GGX distribution for stdlib/pbr.spire's specularGGXLut
// (the Couch example's specular:GGX_tex). Texel (x, y) holds
// D(n.h, alpha) / D(1, alpha) = (alpha^2 / (alpha^2 + s (1 - alpha^2)))^2,
// the distribution scaled by its peak D(1, alpha) = 1 / (pi alpha^2) so that
// it lies in [0, 1], with s = sin^2(theta_h) = 1 - n.h^2, at texel centres:
// sin(theta_h) = (x + 0.5) / size and perceptual roughness r = (y + 0.5) / size,
// alpha = max(r^2, kGgxMinAlpha). Indexing by sin(theta_h) rather than n.h
// spends the texels on the peak, which at low roughness is narrower than a
// texel of n.h. The value is 16-bit fixed point, q = round(value * 65535),
// split over R (q >> 8) and G (q & 255), because 8 bits would flatten the
// tails that make GGX look like GGX; decoding is linear in R and G, so
// bilinear filtering of the bytes filters the value. B is 0, A is 255.
// In any other `format` the value itself is in both R and G (B = 0, A = 1):
// a shader can read R, and specularGGXLut's decode, R * 65280 / 65535 +
// G * 255 / 65535, gives the value too (except in R32F, which has no G).
Image makeGgxLut(uint32_t size, PixelFormat format = PixelFormat::RGBA8);

// Decodes an encoded image file (PNG, JPEG, Radiance .hdr; other formats
// stb_image knows work too) keeping its precision: .hdr gives RGBA32F, a
// 16-bit PNG RGBA16, anything else RGBA8. Missing channels are 0 (color) and
// 1 (alpha), and grey images are spread over R, G and B, as stb_image does.
Expected<Image> decodeImage(std::span<const uint8_t> encoded);

// decodeImage of a file, the errors naming it.
Expected<Image> loadImage(const std::filesystem::path& path);

// `image` as the bytes of a PNG file; an error for an empty image, one that
// is not RGBA8, or pixel data that does not match its size.
Expected<std::string> encodePng(const Image& image);

// Encodes `image` as PNG. The data goes to a temporary file beside `path` that
// is renamed over it, so readers never see a half-written file.
Expected<void> writePng(const std::filesystem::path& path, const Image& image);

}  // namespace spire::scene

#pragma once

// RGBA8 images: procedural generators for the demo's materials, and PNG/JPEG
// file I/O. Rows are stored top to bottom, 4 bytes per pixel.

#include "scene/expected.h"

#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace spire::scene {

using Rgba8 = glm::u8vec4;

struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba8;  // width * height * 4 bytes

  [[nodiscard]] Rgba8 pixel(uint32_t x, uint32_t y) const;
};

// size x size checkerboard of cells x cells squares; the top-left is colorA.
Image makeChecker(uint32_t size, uint32_t cells, Rgba8 colorA, Rgba8 colorB);

// Grey fBm noise (opaque); a given seed gives identical bytes everywhere.
Image makeNoise(uint32_t size, uint32_t seed, uint32_t octaves);

// Tangent-space normal map of a noise heightfield, RGB = n * 0.5 + 0.5.
// +X follows increasing u (image x), +Y increasing v (image rows), matching the
// tangent/bitangent of computeTangents; `strength` scales the slopes.
Image makeNormalMap(uint32_t size, uint32_t seed, float strength);

Image makeSolid(uint32_t size, Rgba8 color);

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
Image makeGgxLut(uint32_t size);

// Decodes a PNG or JPEG file to RGBA8 (other formats stb_image knows work too).
Expected<Image> loadImage(const std::filesystem::path& path);

// `image` as the bytes of a PNG file; an error for an empty image or pixel
// data that does not match its size.
Expected<std::string> encodePng(const Image& image);

// Encodes `image` as PNG. The data goes to a temporary file beside `path` that
// is renamed over it, so readers never see a half-written file.
Expected<void> writePng(const std::filesystem::path& path, const Image& image);

}  // namespace spire::scene

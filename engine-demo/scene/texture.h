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

// Decodes a PNG or JPEG file to RGBA8 (other formats stb_image knows work too).
Expected<Image> loadImage(const std::filesystem::path& path);

// Encodes `image` as PNG. The data goes to a temporary file beside `path` that
// is renamed over it, so readers never see a half-written file.
Expected<void> writePng(const std::filesystem::path& path, const Image& image);

}  // namespace spire::scene

#include "scene/texture.h"

#include "scene/noise.h"
#include "support/file_io.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <system_error>

namespace spire::scene {
namespace {

constexpr float kNoiseFeatures = 8.0f;  // lattice cells across a noise texture

Image blank(uint32_t size) {
  Image image;
  image.width = size;
  image.height = size;
  image.rgba8.resize(static_cast<size_t>(size) * size * 4);
  return image;
}

void setPixel(Image& image, uint32_t x, uint32_t y, Rgba8 color) {
  size_t offset = (static_cast<size_t>(y) * image.width + x) * 4;
  for (int c = 0; c < 4; ++c) image.rgba8[offset + static_cast<size_t>(c)] = color[c];
}

uint8_t toUnorm8(float value) { return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

}  // namespace

Rgba8 Image::pixel(uint32_t x, uint32_t y) const {
  size_t offset = (static_cast<size_t>(y) * width + x) * 4;
  return {rgba8[offset], rgba8[offset + 1], rgba8[offset + 2], rgba8[offset + 3]};
}

Image makeChecker(uint32_t size, uint32_t cells, Rgba8 colorA, Rgba8 colorB) {
  cells = std::max(cells, 1u);
  Image image = blank(size);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      // 64-bit products: size * cells may overflow 32 bits for large images.
      uint64_t cx = static_cast<uint64_t>(x) * cells / size;
      uint64_t cy = static_cast<uint64_t>(y) * cells / size;
      setPixel(image, x, y, (cx + cy) % 2 == 0 ? colorA : colorB);
    }
  }
  return image;
}

Image makeNoise(uint32_t size, uint32_t seed, uint32_t octaves) {
  Image image = blank(size);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      float u = static_cast<float>(x) / static_cast<float>(size);
      float v = static_cast<float>(y) / static_cast<float>(size);
      uint8_t grey = toUnorm8(fbm(u * kNoiseFeatures, v * kNoiseFeatures, seed, octaves));
      setPixel(image, x, y, Rgba8(grey, grey, grey, 255));
    }
  }
  return image;
}

Image makeNormalMap(uint32_t size, uint32_t seed, float strength) {
  constexpr uint32_t kOctaves = 4;
  Image image = blank(size);
  float texel = 1.0f / static_cast<float>(std::max(size, 1u));
  auto heightAt = [&](float u, float v) { return fbm(u * kNoiseFeatures, v * kNoiseFeatures, seed, kOctaves); };
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      float u = static_cast<float>(x) * texel;
      float v = static_cast<float>(y) * texel;
      // Central differences of the continuous height function (so the border
      // needs no clamping or wrapping), as slopes per noise-lattice cell so that
      // `strength` means the same at every texture size.
      float dhdu = (heightAt(u + texel, v) - heightAt(u - texel, v)) * 0.5f / texel * (1.0f / kNoiseFeatures);
      float dhdv = (heightAt(u, v + texel) - heightAt(u, v - texel)) * 0.5f / texel * (1.0f / kNoiseFeatures);
      glm::vec3 n = glm::normalize(glm::vec3(-strength * dhdu, -strength * dhdv, 1.0f));
      glm::vec3 encoded = n * 0.5f + 0.5f;
      setPixel(image, x, y, Rgba8(toUnorm8(encoded.x), toUnorm8(encoded.y), toUnorm8(encoded.z), 255));
    }
  }
  return image;
}

Image makeSolid(uint32_t size, Rgba8 color) {
  Image image = blank(size);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) setPixel(image, x, y, color);
  }
  return image;
}

Image makeGgxLut(uint32_t size) {
  Image image = blank(size);
  const double texel = 1.0 / static_cast<double>(size);
  for (uint32_t y = 0; y < size; ++y) {
    const double roughness = (y + 0.5) * texel;
    const double alpha = std::max(roughness * roughness, static_cast<double>(kGgxMinAlpha));
    const double alpha2 = alpha * alpha;
    for (uint32_t x = 0; x < size; ++x) {
      const double sinTheta = (x + 0.5) * texel;
      const double ratio = alpha2 / (alpha2 + sinTheta * sinTheta * (1.0 - alpha2));
      const auto q = static_cast<uint32_t>(std::lround(ratio * ratio * 65535.0));
      setPixel(image, x, y, Rgba8(static_cast<uint8_t>(q >> 8), static_cast<uint8_t>(q & 0xFF), 0, 255));
    }
  }
  return image;
}

Expected<Image> loadImage(const std::filesystem::path& path) {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &width, &height, &channels, STBI_rgb_alpha),
                                                   stbi_image_free);
  if (!pixels) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      return Error{"cannot load image '" + path.string() + "': file does not exist or is not a regular file"};
    }
    return Error{"cannot load image '" + path.string() + "': " + stbi_failure_reason()};
  }
  Image image;
  image.width = static_cast<uint32_t>(width);
  image.height = static_cast<uint32_t>(height);
  image.rgba8.assign(pixels.get(), pixels.get() + static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  return image;
}

Expected<std::string> encodePng(const Image& image) {
  if (image.width == 0 || image.height == 0 ||
      image.rgba8.size() != static_cast<size_t>(image.width) * image.height * 4) {
    return Error{"the image is empty or its pixel data does not match " + std::to_string(image.width) + "x" +
                 std::to_string(image.height) + " RGBA8"};
  }
  std::string encoded;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  const int stride = static_cast<int>(image.width) * 4;
  if (stbi_write_png_to_func(append, &encoded, static_cast<int>(image.width), static_cast<int>(image.height), 4,
                             image.rgba8.data(), stride) == 0) {
    return Error{"the PNG encoder failed"};
  }
  return encoded;
}

Expected<void> writePng(const std::filesystem::path& path, const Image& image) {
  auto encoded = encodePng(image);
  if (!encoded) return Error{"cannot write PNG '" + path.string() + "': " + encoded.error().message};
  return writeFileAtomically(path.string(), *encoded);
}

}  // namespace spire::scene

#include "scene/texture.h"

#include "scene/noise.h"
#include "support/file_io.h"

#include <fmt/format.h>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>
#include <system_error>

namespace spire::scene {
namespace {

constexpr float kNoiseFeatures = 8.0f;  // lattice cells across a noise texture

size_t texelOffset(const Image& image, uint32_t x, uint32_t y) {
  return (static_cast<size_t>(y) * image.width + x) * texelBytes(image.format);
}

Image blank(uint32_t size, PixelFormat format = PixelFormat::RGBA8) { return makeImage(size, size, format); }

void setPixel(Image& image, uint32_t x, uint32_t y, Rgba8 color) {
  size_t offset = texelOffset(image, x, y);
  for (int c = 0; c < 4; ++c) image.bytes[offset + static_cast<size_t>(c)] = color[c];
}

// The checker cell of (x, y) is even: the top-left cell's color.
bool evenCell(uint32_t x, uint32_t y, uint32_t size, uint32_t cells) {
  // 64-bit products: size * cells may overflow 32 bits for large images.
  uint64_t cx = static_cast<uint64_t>(x) * cells / size;
  uint64_t cy = static_cast<uint64_t>(y) * cells / size;
  return (cx + cy) % 2 == 0;
}

// D(n.h, alpha) / D(1, alpha) at the centre of texel (x, y) (texture.h).
double ggxRatio(uint32_t size, uint32_t x, uint32_t y) {
  const double texel = 1.0 / static_cast<double>(size);
  const double roughness = (y + 0.5) * texel;
  const double alpha = std::max(roughness * roughness, static_cast<double>(kGgxMinAlpha));
  const double alpha2 = alpha * alpha;
  const double sinTheta = (x + 0.5) * texel;
  const double ratio = alpha2 / (alpha2 + sinTheta * sinTheta * (1.0 - alpha2));
  return ratio * ratio;
}

// Takes ownership of what an stbi_load* call returned: width x height texels
// of 4 channels of T.
template <typename T>
Expected<Image> adoptPixels(T* decoded, int width, int height, PixelFormat format) {
  std::unique_ptr<T, void (*)(void*)> pixels(decoded, stbi_image_free);
  if (!pixels) return Error{stbi_failure_reason()};
  Image image;
  image.width = static_cast<uint32_t>(width);
  image.height = static_cast<uint32_t>(height);
  image.format = format;
  const auto* first = reinterpret_cast<const uint8_t*>(pixels.get());
  image.bytes.assign(first, first + static_cast<size_t>(width) * static_cast<size_t>(height) * 4 * sizeof(T));
  return image;
}

}  // namespace

Rgba8 Image::pixel(uint32_t x, uint32_t y) const {
  size_t offset = texelOffset(*this, x, y);
  return {bytes[offset], bytes[offset + 1], bytes[offset + 2], bytes[offset + 3]};
}

glm::vec4 Image::texel(uint32_t x, uint32_t y) const {
  return decodeTexel(format, std::span(bytes).subspan(texelOffset(*this, x, y), texelBytes(format)));
}

void Image::setTexel(uint32_t x, uint32_t y, const glm::vec4& value) {
  encodeTexel(format, value, std::span(bytes).subspan(texelOffset(*this, x, y), texelBytes(format)));
}

bool Image::consistent() const { return bytes.size() == static_cast<size_t>(width) * height * texelBytes(format); }

Image makeImage(uint32_t width, uint32_t height, PixelFormat format) {
  return Image{width, height, std::vector<uint8_t>(static_cast<size_t>(width) * height * texelBytes(format)), format};
}

Image convertImage(Image image, PixelFormat format) {
  if (image.format == format) return image;
  Image converted = makeImage(image.width, image.height, format);
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) converted.setTexel(x, y, image.texel(x, y));
  }
  return converted;
}

Image makeChecker(uint32_t size, uint32_t cells, Rgba8 colorA, Rgba8 colorB) {
  cells = std::max(cells, 1u);
  Image image = blank(size);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) setPixel(image, x, y, evenCell(x, y, size, cells) ? colorA : colorB);
  }
  return image;
}

Image makeChecker(uint32_t size, uint32_t cells, const glm::vec4& colorA, const glm::vec4& colorB, PixelFormat format) {
  cells = std::max(cells, 1u);
  Image image = blank(size, format);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) image.setTexel(x, y, evenCell(x, y, size, cells) ? colorA : colorB);
  }
  return image;
}

Image makeNoise(uint32_t size, uint32_t seed, uint32_t octaves, PixelFormat format) {
  Image image = blank(size, format);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      float u = static_cast<float>(x) / static_cast<float>(size);
      float v = static_cast<float>(y) / static_cast<float>(size);
      float grey = std::clamp(fbm(u * kNoiseFeatures, v * kNoiseFeatures, seed, octaves), 0.0f, 1.0f);
      image.setTexel(x, y, glm::vec4(grey, grey, grey, 1.0f));
    }
  }
  return image;
}

Image makeNormalMap(uint32_t size, uint32_t seed, float strength, PixelFormat format) {
  constexpr uint32_t kOctaves = 4;
  Image image = blank(size, format);
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
      image.setTexel(x, y, glm::vec4(n * 0.5f + 0.5f, 1.0f));
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

Image makeSolid(uint32_t size, const glm::vec4& color, PixelFormat format) {
  Image image = blank(size, format);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) image.setTexel(x, y, color);
  }
  return image;
}

Image makeGgxLut(uint32_t size, PixelFormat format) {
  Image image = blank(size, format);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const double value = ggxRatio(size, x, y);
      if (format == PixelFormat::RGBA8) {
        const auto q = static_cast<uint32_t>(std::lround(value * 65535.0));
        setPixel(image, x, y, Rgba8(static_cast<uint8_t>(q >> 8), static_cast<uint8_t>(q & 0xFF), 0, 255));
      } else {
        const auto stored = static_cast<float>(value);
        image.setTexel(x, y, glm::vec4(stored, stored, 0.0f, 1.0f));
      }
    }
  }
  return image;
}

Expected<Image> decodeImage(std::span<const uint8_t> encoded) {
  if (encoded.empty() || encoded.size() > static_cast<size_t>(INT_MAX)) {
    return Error{fmt::format("encoded image size {} is out of range", encoded.size())};
  }
  const stbi_uc* data = encoded.data();
  const int size = static_cast<int>(encoded.size());
  int width = 0;
  int height = 0;
  int channels = 0;
  if (stbi_is_hdr_from_memory(data, size) != 0) {
    float* pixels = stbi_loadf_from_memory(data, size, &width, &height, &channels, STBI_rgb_alpha);
    return adoptPixels(pixels, width, height, PixelFormat::RGBA32F);
  }
  if (stbi_is_16_bit_from_memory(data, size) != 0) {
    stbi_us* pixels = stbi_load_16_from_memory(data, size, &width, &height, &channels, STBI_rgb_alpha);
    return adoptPixels(pixels, width, height, PixelFormat::RGBA16);
  }
  stbi_uc* pixels = stbi_load_from_memory(data, size, &width, &height, &channels, STBI_rgb_alpha);
  return adoptPixels(pixels, width, height, PixelFormat::RGBA8);
}

Expected<Image> loadImage(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return Error{"cannot load image '" + path.string() + "': file does not exist or is not a regular file"};
  }
  auto encoded = readFileBytes(path.string());
  if (!encoded) return Error{"cannot load image '" + path.string() + "': " + encoded.error().message()};
  auto image = decodeImage(std::span(reinterpret_cast<const uint8_t*>(encoded->data()), encoded->size()));
  if (!image) return Error{"cannot load image '" + path.string() + "': " + image.error().message};
  return image;
}

Expected<std::string> encodePng(const Image& image) {
  if (image.format != PixelFormat::RGBA8) {
    return Error{fmt::format("PNG output takes RGBA8 images, not {}", pixelFormatName(image.format))};
  }
  if (image.width == 0 || image.height == 0 || !image.consistent()) {
    return Error{"the image is empty or its pixel data does not match " + std::to_string(image.width) + "x" +
                 std::to_string(image.height) + " RGBA8"};
  }
  std::string encoded;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  const int stride = static_cast<int>(image.width) * 4;
  if (stbi_write_png_to_func(append, &encoded, static_cast<int>(image.width), static_cast<int>(image.height), 4,
                             image.bytes.data(), stride) == 0) {
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

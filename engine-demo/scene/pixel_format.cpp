#include "scene/pixel_format.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace spire::scene {
namespace {

constexpr float kMaxHalf = 65504.0F;

template <typename T>
T unorm(float value) {
  constexpr float kMax = static_cast<float>(std::numeric_limits<T>::max());
  if (!(value > 0.0F)) return 0;  // also maps NaN to 0
  return static_cast<T>(std::lround(std::min(value, 1.0F) * kMax));
}

template <typename T>
void store(std::span<uint8_t> out, size_t index, T value) {
  std::memcpy(out.data() + index * sizeof(T), &value, sizeof(T));
}

template <typename T>
T load(std::span<const uint8_t> in, size_t index) {
  T value{};
  std::memcpy(&value, in.data() + index * sizeof(T), sizeof(T));
  return value;
}

uint16_t half(float value) {
  // glm's conversion overflows to infinity; a bright .hdr texel should stay
  // the brightest finite half instead.
  if (std::isfinite(value)) value = std::clamp(value, -kMaxHalf, kMaxHalf);
  return glm::packHalf1x16(value);
}

}  // namespace

std::string_view pixelFormatName(PixelFormat format) {
  for (const PixelFormatName& entry : kPixelFormats) {
    if (entry.format == format) return entry.name;
  }
  return "?";
}

std::optional<PixelFormat> pixelFormatNamed(std::string_view name) {
  for (const PixelFormatName& entry : kPixelFormats) {
    if (entry.name == name) return entry.format;
  }
  return std::nullopt;
}

size_t texelBytes(PixelFormat format) {
  switch (format) {
    case PixelFormat::RGBA8: return 4;
    case PixelFormat::RGBA16:
    case PixelFormat::RGBA16F: return 8;
    case PixelFormat::RGBA32F: return 16;
    case PixelFormat::R32F: return 4;
  }
  return 0;
}

PixelFormat widerFormat(PixelFormat a, PixelFormat b) {
  if (a == b && a != PixelFormat::R32F) return a;
  const auto isUnorm = [](PixelFormat f) { return f == PixelFormat::RGBA8 || f == PixelFormat::RGBA16; };
  return isUnorm(a) && isUnorm(b) ? PixelFormat::RGBA16 : PixelFormat::RGBA32F;
}

void encodeTexel(PixelFormat format, const glm::vec4& value, std::span<uint8_t> out) {
  for (glm::length_t c = 0; c < 4; ++c) {
    const auto i = static_cast<size_t>(c);
    switch (format) {
      case PixelFormat::RGBA8: out[i] = unorm<uint8_t>(value[c]); break;
      case PixelFormat::RGBA16: store(out, i, unorm<uint16_t>(value[c])); break;
      case PixelFormat::RGBA16F: store(out, i, half(value[c])); break;
      case PixelFormat::RGBA32F: store(out, i, value[c]); break;
      case PixelFormat::R32F:
        if (c == 0) store(out, 0, value.r);
        break;
    }
  }
}

glm::vec4 decodeTexel(PixelFormat format, std::span<const uint8_t> in) {
  glm::vec4 value(0.0F, 0.0F, 0.0F, 1.0F);
  for (glm::length_t c = 0; c < 4; ++c) {
    const auto i = static_cast<size_t>(c);
    switch (format) {
      case PixelFormat::RGBA8: value[c] = static_cast<float>(in[i]) / 255.0F; break;
      case PixelFormat::RGBA16: value[c] = static_cast<float>(load<uint16_t>(in, i)) / 65535.0F; break;
      case PixelFormat::RGBA16F: value[c] = glm::unpackHalf1x16(load<uint16_t>(in, i)); break;
      case PixelFormat::RGBA32F: value[c] = load<float>(in, i); break;
      case PixelFormat::R32F:
        if (c == 0) value.r = load<float>(in, 0);
        break;
    }
  }
  return value;
}

}  // namespace spire::scene

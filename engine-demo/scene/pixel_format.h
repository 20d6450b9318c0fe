#pragma once

// The texel layouts of scene images, which are also the GPU formats their
// textures are uploaded in. Names are those of the scene file's "format" key,
// spelled like the bake formats of renderer/texture_bake.cpp ("RGBA16" is
// 16-bit unorm, which bakes do not use). Texels are stored as a buffer copy
// hands them to the GPU: host byte order, RGBA order, no sRGB.

#include <glm/vec4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace spire::scene {

enum class PixelFormat : uint8_t { RGBA8, RGBA16, RGBA16F, RGBA32F, R32F };

struct PixelFormatName {
  std::string_view name;
  PixelFormat format;
};

inline constexpr std::array<PixelFormatName, 5> kPixelFormats = {{
    {"RGBA8", PixelFormat::RGBA8},
    {"RGBA16", PixelFormat::RGBA16},
    {"RGBA16F", PixelFormat::RGBA16F},
    {"RGBA32F", PixelFormat::RGBA32F},
    {"R32F", PixelFormat::R32F},
}};

std::string_view pixelFormatName(PixelFormat format);
std::optional<PixelFormat> pixelFormatNamed(std::string_view name);

size_t texelBytes(PixelFormat format);

// The format of fewest bytes that holds the texels of both `a` and `b`
// without loss: one of them when it holds the other (RGBA8 in RGBA16, any
// format in RGBA32F), else RGBA32F. R32F gives RGBA32F, so that all four
// channels of the other survive. Unorm values k / 255 and k / 65535 count as
// held by RGBA32F: they read back as the same nearest float.
PixelFormat widerFormat(PixelFormat a, PixelFormat b);

// Writes `value` as one texel of `format` into `out` (texelBytes(format)
// bytes). Unorm channels clamp to [0, 1] and round to nearest (NaN gives 0),
// RGBA16F rounds to the nearest half and clamps finite values to the half
// range (+-65504), R32F keeps red only.
void encodeTexel(PixelFormat format, const glm::vec4& value, std::span<uint8_t> out);

// The texel at `in` as a shader samples it: unorm k as k / (2^n - 1), R32F as
// (r, 0, 0, 1).
glm::vec4 decodeTexel(PixelFormat format, std::span<const uint8_t> in);

}  // namespace spire::scene

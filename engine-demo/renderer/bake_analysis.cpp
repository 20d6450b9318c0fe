#include "renderer/bake_analysis.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "renderer/value_layout.h"

namespace spire::engine {

namespace {

constexpr float kUnitTolerance = 0.02F;
constexpr float kHalfMax = 65504.0F;

std::string chooseFormat(BakeLayout& layout) {
  const uint32_t n = layout.channels;
  bool unit = true;
  float magnitude = 0.0F;
  for (uint32_t c = 0; c < n; ++c) {
    unit = unit && layout.minimum[c] >= 0.0F && layout.maximum[c] <= 1.0F;
    magnitude = std::max({magnitude, std::abs(layout.minimum[c]), std::abs(layout.maximum[c])});
  }
  if (!layout.finite) return n == 1 ? "R32F" : "RGBA32F";
  if (unit) return n == 1 ? "R8" : n == 2 ? "RG8" : "RGBA8";
  // RGB10_A2 keeps 2 bits of alpha: enough only for a vec3 or an alpha of 0 or 1.
  const bool alphaFits =
      n == 3 || (layout.minimum[3] >= 0.0F && layout.maximum[3] <= 1.0F && (layout.minimum[3] == layout.maximum[3]));
  if (layout.unitVectors && alphaFits) {
    layout.signedEncoding = true;
    return "RGB10_A2";
  }
  if (magnitude <= kHalfMax) return n == 1 ? "R16F" : n == 2 ? "RG16F" : "RGBA16F";
  return n == 1 ? "R32F" : "RGBA32F";
}

}  // namespace

BakeLayout analyzeBakedValues(std::string component, uint32_t channels, std::span<const float> rgba,
                              std::span<const uint8_t> coverage) {
  BakeLayout layout;
  layout.component = std::move(component);
  layout.channels = channels;
  layout.minimum.fill(std::numeric_limits<float>::infinity());
  layout.maximum.fill(-std::numeric_limits<float>::infinity());
  bool unit = channels >= 3;
  for (size_t i = 0; i < coverage.size() && (i + 1) * 4 <= rgba.size(); ++i) {
    if (!coverage[i]) continue;
    const float* v = rgba.data() + i * 4;
    for (uint32_t c = 0; c < 4; ++c) {
      layout.finite = layout.finite && std::isfinite(v[c]);
      layout.minimum[c] = std::min(layout.minimum[c], v[c]);
      layout.maximum[c] = std::max(layout.maximum[c], v[c]);
    }
    if (unit) unit = std::abs(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0F) <= kUnitTolerance;
  }
  layout.unitVectors = unit;
  layout.format = chooseFormat(layout);
  return layout;
}

Expected<std::vector<BakeLayout>> selectBakeLayouts(const KernelProgram& kernel, const TextureBakeResult& baked) {
  std::vector<BakeLayout> layouts;
  for (const KernelOutput& output : kernel.outputs) {
    if (output.kind != OutputKind::Varying) continue;
    const auto texture = baked.textures.find(output.component);
    const ValueType* type = output.type.isNumeric() ? &output.type : nullptr;
    if (texture == baked.textures.end() || !type) continue;
    const std::vector<std::byte>& texels = texture->second.texels;
    const size_t count = size_t{baked.size} * baked.size;
    if (texels.size() != count * 4 * sizeof(float) || baked.coverage.size() != count) {
      return Error{fmt::format("'{}' was not baked in RGBA32F with its texels kept", output.component), {}, {}};
    }
    std::vector<float> rgba(count * 4);
    std::memcpy(rgba.data(), texels.data(), texels.size());
    layouts.push_back(analyzeBakedValues(output.component, type->rows, rgba, baked.coverage));
  }
  return layouts;
}

}  // namespace spire::engine

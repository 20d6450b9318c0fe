// Data-layout selection for PrebakeTex outputs (paper section 7.4): from the
// values a bake actually produced (baked in RGBA32F), pick the smallest
// storage format that holds them: 8-bit unorm for values in [0, 1],
// RGB10_A2 with a signed remap for unit vectors, half floats otherwise, with
// fewer channels when the component has fewer.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "renderer/kernel_bindings.h"
#include "renderer/variant_program.h"

namespace spire::engine {

struct BakeLayout {
  std::string component;
  uint32_t channels = 4;  // components of the value's type
  std::array<float, 4> minimum{};
  std::array<float, 4> maximum{};
  bool finite = true;
  bool unitVectors = false;     // xyz of every covered texel has length 1 (within 2%)
  std::string format;           // a Format hint name (texture_bake.h)
  bool signedEncoding = false;  // store v * 0.5 + 0.5 ([Encoding: "signed"])
};

// Analyses one output from its RGBA32F texels (4 floats each) where
// `coverage` is non-zero, keeping the first `channels` components.
BakeLayout analyzeBakedValues(std::string component, uint32_t channels, std::span<const float> rgba,
                              std::span<const uint8_t> coverage);

// Analyses every output of the PrebakeTex `kernel` in `baked`, which must have
// been baked with TextureBakeOptions::forceFormat = RGBA32F.
Expected<std::vector<BakeLayout>> selectBakeLayouts(const KernelProgram& kernel, const TextureBakeResult& baked);

}  // namespace spire::engine

// SPIR-V already made in this process, by kernel text: variants of one
// shader often share a kernel (in the examples, 51 distinct of 81 kernels
// across the default variants and decision files), and `spirec --batch`
// compiles many variants in one process. Making SPIR-V from GLSL is a pure
// function of the stage, the text and its name, so a hit is exactly what
// glslang and the validator would give.
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "codegen/spirv_compiler.h"

namespace spire {

class SpirvCache {
 public:
  // The validated SPIR-V of a kernel made before; nullopt when not cached.
  std::optional<std::vector<uint32_t>> find(codegen::ShaderStage stage, std::string_view name,
                                            std::string_view glsl) const;
  // Remembers a kernel that compiled and validated. Only valid kernels are
  // kept, so that a rejected one is reported by the same path every time.
  // Past kMaxKeyBytes of kernel text nothing more is kept: a batch of
  // thousands of shaders must not grow without bound.
  void add(codegen::ShaderStage stage, std::string_view name, std::string_view glsl, std::vector<uint32_t> words);

  static constexpr size_t kMaxKeyBytes = size_t{256} << 20;

 private:
  static std::string key(codegen::ShaderStage stage, std::string_view name, std::string_view glsl);

  mutable std::mutex mutex_;
  std::unordered_map<std::string, std::vector<uint32_t>> kernels_;
  size_t keyBytes_ = 0;
};

}  // namespace spire

#include "driver/spirv_cache.h"

namespace spire {

std::string SpirvCache::key(codegen::ShaderStage stage, std::string_view name, std::string_view glsl) {
  // The name cannot hold a NUL byte (it is a file name), so the key is
  // unambiguous.
  std::string key = std::to_string(static_cast<int>(stage));
  key += '\0';
  key += name;
  key += '\0';
  key += glsl;
  return key;
}

std::optional<std::vector<uint32_t>> SpirvCache::find(codegen::ShaderStage stage, std::string_view name,
                                                      std::string_view glsl) const {
  const std::string wanted = key(stage, name, glsl);
  const std::lock_guard lock(mutex_);
  const auto found = kernels_.find(wanted);
  if (found == kernels_.end()) return std::nullopt;
  return found->second;
}

void SpirvCache::add(codegen::ShaderStage stage, std::string_view name, std::string_view glsl,
                     std::vector<uint32_t> words) {
  std::string added = key(stage, name, glsl);
  const std::lock_guard lock(mutex_);
  if (keyBytes_ + added.size() > kMaxKeyBytes) return;
  keyBytes_ += added.size();
  kernels_.try_emplace(std::move(added), std::move(words));
}

}  // namespace spire

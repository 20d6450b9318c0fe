#include "renderer/module_cache.h"

#include "vk/pipeline.h"

namespace spire::engine {

Expected<VkShaderModule> ModuleCache::get(const vk::Context& ctx, const std::string& key,
                                          std::span<const uint32_t> words) {
  if (const auto it = modules_.find(key); it != modules_.end()) return it->second.get();
  auto module = vk::createShaderModule(ctx, words);
  if (!module) return Error::fromVk(module.error());
  return modules_.emplace(key, std::move(module).value()).first->second.get();
}

VkShaderModule ModuleCache::find(const std::string& key) const {
  const auto it = modules_.find(key);
  return it == modules_.end() ? VK_NULL_HANDLE : it->second.get();
}

}  // namespace spire::engine

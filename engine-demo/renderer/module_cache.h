// Shader modules keyed by the kernel's content hash (docs/reflection.md): a
// kernel shared by several variants, or by instances, is created once.
#pragma once

#include <map>
#include <span>
#include <string>

#include "renderer/error.h"
#include "vk/context.h"
#include "vk/handle.h"

namespace spire::engine {

class ModuleCache {
 public:
  // The module for `key`, created from `words` the first time the key is seen.
  Expected<VkShaderModule> get(const vk::Context& ctx, const std::string& key, std::span<const uint32_t> words);
  // The module for `key` if one was created, so that a caller that must
  // compile the words first can skip that: VK_NULL_HANDLE otherwise.
  VkShaderModule find(const std::string& key) const;
  size_t size() const { return modules_.size(); }

 private:
  std::map<std::string, vk::ShaderModule> modules_;
};

}  // namespace spire::engine

// The descriptor sets of one pipeline (a draw's Vertex and Fragment kernels,
// a compute bake, the texture bake): the bindings of its kernels merged per
// set number as reflection gives them (docs/reflection.md, Descriptor
// bindings), one layout per set, and the sets written and bound together.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "renderer/kernel_bindings.h"
#include "vk/pipeline.h"

namespace spire::engine {

// One binding of one set: the descriptor, with the stages of every kernel
// that uses it.
struct MergedBinding {
  BoundDescriptor descriptor;
  VkShaderStageFlags stages = 0;
  std::string world;  // the first kernel that uses it, for messages
};

// By set number, from 0 to the highest number a kernel uses; a number no
// kernel uses is an empty set (a pipeline layout has no gaps). Within a set,
// bindings in increasing order.
using DescriptorSetPlan = std::vector<std::vector<MergedBinding>>;

// Merges the kernels' descriptors. Kernels that use the same (set, binding)
// for the same resource share it (their stage flags are merged); for a
// different descriptor type or a different resource it is an error, as is a
// set number of `maxSets` or more (the device's maxBoundDescriptorSets).
Expected<DescriptorSetPlan> planDescriptorSets(std::span<const BoundKernel* const> kernels, uint32_t maxSets);

struct DescriptorBundle {
  std::vector<vk::DescriptorSetLayout> layouts;  // by set number
  vk::DescriptorPool pool;                       // none when there are no sets
  std::vector<VkDescriptorSet> sets;             // by set number; freed with the pool
  // The layouts' definitions as text: a pipeline built over other layouts
  // with the same key is compatible with these sets (Vulkan's "identically
  // defined" layouts), so pipeline caches key on it.
  std::string layoutKey;

  // The layouts' handles, in set order, for a pipeline layout.
  std::vector<VkDescriptorSetLayout> layoutHandles() const;
};

// Creates the layouts, allocates every set (empty ones included) and writes
// the kernels' descriptors into them.
Expected<DescriptorBundle> createDescriptors(const vk::Context& ctx, std::span<const BoundKernel* const> kernels);

// Binds all of the bundle's sets, from set 0; nothing when there are none.
void bindDescriptors(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout,
                     const DescriptorBundle& bundle);

}  // namespace spire::engine

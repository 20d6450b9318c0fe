#include "renderer/pipeline_descriptors.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace spire::engine {

namespace {

std::string_view typeName(VkDescriptorType type) {
  switch (type) {
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return "uniform buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return "storage buffer";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return "combined image sampler";
    default: return "descriptor";
  }
}

// `used` is already at `added`'s slot: shares it, or says why it cannot.
Expected<void> merge(MergedBinding& used, const BoundDescriptor& added, const BoundKernel& kernel) {
  const BoundDescriptor& first = used.descriptor;
  const auto where = [&] {
    return fmt::format("the {} and {} kernels both use descriptor set {}, binding {}", used.world, kernel.world,
                       first.slot.set, first.slot.binding);
  };
  if (first.type != added.type) {
    return Error{fmt::format("{}, with different types: {} as a {} in {}, {} as a {} in {}", where(), first.what,
                             typeName(first.type), used.world, added.what, typeName(added.type), kernel.world),
                 {},
                 {}};
  }
  if (!first.sameResource(added)) {
    return Error{fmt::format("{} for different resources ({} in {}, {} in {})", where(), first.what, used.world,
                             added.what, kernel.world),
                 {},
                 {}};
  }
  used.stages |= kernel.stage;
  return {};
}

void writeSet(const vk::Context& ctx, VkDescriptorSet set, const std::vector<MergedBinding>& bindings) {
  vk::DescriptorWriter writer;
  for (const MergedBinding& b : bindings) {
    const BoundDescriptor& d = b.descriptor;
    if (d.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) {
      writer.image(d.slot.binding, d.type, d.view, d.sampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    } else {
      writer.buffer(d.slot.binding, d.type, d.buffer);
    }
  }
  writer.update(ctx, set);
}

}  // namespace

Expected<DescriptorSetPlan> planDescriptorSets(std::span<const BoundKernel* const> kernels, uint32_t maxSets) {
  std::map<DescriptorSlot, MergedBinding> merged;
  for (const BoundKernel* kernel : kernels) {
    for (const BoundDescriptor& descriptor : kernel->descriptors) {
      if (descriptor.slot.set >= maxSets) {
        return Error{fmt::format("the {} kernel's {} is in descriptor set {}, but the device binds at most {} sets",
                                 kernel->world, descriptor.what, descriptor.slot.set, maxSets),
                     {},
                     {}};
      }
      const auto [it, inserted] =
          merged.try_emplace(descriptor.slot, MergedBinding{descriptor, kernel->stage, kernel->world});
      if (inserted) continue;
      auto shared = merge(it->second, descriptor, *kernel);
      if (!shared) return shared.error();
    }
  }
  DescriptorSetPlan plan;
  if (!merged.empty()) plan.resize(size_t{merged.rbegin()->first.set} + 1);
  // The map is ordered by (set, binding), so each set's bindings come sorted.
  for (auto& [slot, binding] : merged) plan[slot.set].push_back(std::move(binding));
  return plan;
}

std::vector<VkDescriptorSetLayout> DescriptorBundle::layoutHandles() const {
  std::vector<VkDescriptorSetLayout> handles;
  for (const vk::DescriptorSetLayout& layout : layouts) handles.push_back(layout.get());
  return handles;
}

Expected<DescriptorBundle> createDescriptors(const vk::Context& ctx, std::span<const BoundKernel* const> kernels) {
  auto plan = planDescriptorSets(kernels, ctx.properties().limits.maxBoundDescriptorSets);
  if (!plan) return plan.error();
  DescriptorBundle bundle;
  std::map<VkDescriptorType, uint32_t> counts;
  for (const std::vector<MergedBinding>& set : *plan) {
    vk::DescriptorSetLayoutBuilder builder;
    bundle.layoutKey += "set";
    for (const MergedBinding& b : set) {
      builder.binding(b.descriptor.slot.binding, b.descriptor.type, b.stages);
      bundle.layoutKey +=
          fmt::format(" {}:{}:{}", b.descriptor.slot.binding, static_cast<int>(b.descriptor.type), b.stages);
      ++counts[b.descriptor.type];
    }
    bundle.layoutKey += ";";
    auto layout = builder.build(ctx);
    if (!layout) return Error::fromVk(layout.error());
    bundle.layouts.push_back(std::move(layout).value());
  }
  if (plan->empty()) return bundle;

  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});
  // A pool needs at least one size even when every set is empty.
  if (sizes.empty()) sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1});
  auto pool = vk::createDescriptorPool(ctx, static_cast<uint32_t>(plan->size()), sizes);
  if (!pool) return Error::fromVk(pool.error());
  bundle.pool = std::move(pool).value();
  for (size_t s = 0; s < plan->size(); ++s) {
    auto set = vk::allocateDescriptorSet(ctx, bundle.pool.get(), bundle.layouts[s].get());
    if (!set) return Error::fromVk(set.error());
    bundle.sets.push_back(*set);
    writeSet(ctx, *set, (*plan)[s]);
  }
  return bundle;
}

void bindDescriptors(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout,
                     const DescriptorBundle& bundle) {
  if (bundle.sets.empty()) return;
  vkCmdBindDescriptorSets(cmd, bindPoint, layout, 0, static_cast<uint32_t>(bundle.sets.size()), bundle.sets.data(), 0,
                          nullptr);
}

}  // namespace spire::engine

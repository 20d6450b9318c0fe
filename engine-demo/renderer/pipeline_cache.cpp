#include "renderer/pipeline_cache.h"

#include <fmt/format.h>

namespace spire::engine {

template <class Build>
Expected<SharedPipeline> PipelineCache::lookup(const std::string& key, Build&& build) {
  if (const auto it = pipelines_.find(key); it != pipelines_.end()) {
    if (SharedPipeline pipeline = it->second.lock()) {
      ++counts_.reused;
      return pipeline;
    }
  }
  auto built = build();
  if (!built) return Error::fromVk(built.error());
  // Entries of pipelines no scene holds any more are dropped here, so the
  // map grows with the pipelines in use, not with every variant prepared.
  std::erase_if(pipelines_, [](const auto& entry) { return entry.second.expired(); });
  auto pipeline = std::make_shared<const vk::Pipeline>(std::move(built).value());
  pipelines_[key] = pipeline;
  ++counts_.created;
  return SharedPipeline(std::move(pipeline));
}

Expected<SharedPipeline> PipelineCache::get(const vk::Context& ctx, const vk::GraphicsPipelineBuilder& builder,
                                            const std::string& shaders, const DescriptorBundle& descriptors) {
  return lookup(fmt::format("{}|{}|{}", shaders, descriptors.layoutKey, builder.stateKey()),
                [&] { return builder.build(ctx); });
}

Expected<SharedPipeline> PipelineCache::getCompute(const vk::Context& ctx, VkShaderModule module,
                                                   const std::string& shaders, const DescriptorBundle& descriptors) {
  return lookup(fmt::format("compute {}|{}", shaders, descriptors.layoutKey),
                [&] { return vk::createComputePipeline(ctx, module, descriptors.layoutHandles()); });
}

}  // namespace spire::engine

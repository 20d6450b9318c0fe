// Graphics pipelines shared by the draws and frame passes of one renderer,
// across its prepared scenes: a tool that prepares the scene again after one
// instance's variant changed (spire-explore) builds pipelines only for the
// kernels that changed, and lavapipe compiles only those at the first draw.
//
// A pipeline is keyed by its kernels' content hashes (docs/reflection.md),
// the builder's state (vk::GraphicsPipelineBuilder::stateKey: target
// formats, blending, depth, culling, vertex layout) and the definitions of
// the descriptor set layouts it is built over, so a reused pipeline is one
// Vulkan would build identically, and compatible with the new draw's sets.
// The cache holds pipelines weakly: one lives as long as a prepared scene
// (or frame pass) that draws with it, so a scene still rendering keeps its
// pipelines however the cache changes, and pipelines of variants no scene
// draws any more are not kept.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>

#include "renderer/error.h"
#include "renderer/module_cache.h"
#include "renderer/pipeline_descriptors.h"
#include "vk/pipeline.h"

namespace spire::engine {

using SharedPipeline = std::shared_ptr<const vk::Pipeline>;

// How many pipelines a renderer built and how many it took from the cache.
struct PipelineCounts {
  size_t created = 0;
  size_t reused = 0;
};

class PipelineCache {
 public:
  // The pipeline of `builder` with shader modules of content `shaders` (the
  // kernels' hashes) over `descriptors`' layouts: one still in use with the
  // same key, or else built now. The builder's set layouts must be
  // `descriptors`'.
  Expected<SharedPipeline> get(const vk::Context& ctx, const vk::GraphicsPipelineBuilder& builder,
                               const std::string& shaders, const DescriptorBundle& descriptors);
  // The compute pipeline of `module` (content `shaders`) over `descriptors`'
  // layouts, the same way.
  Expected<SharedPipeline> getCompute(const vk::Context& ctx, VkShaderModule module, const std::string& shaders,
                                      const DescriptorBundle& descriptors);
  // Since the renderer was made.
  const PipelineCounts& counts() const { return counts_; }

 private:
  template <class Build>
  Expected<SharedPipeline> lookup(const std::string& key, Build&& build);

  std::map<std::string, std::weak_ptr<const vk::Pipeline>> pipelines_;
  PipelineCounts counts_;
};

// Where draws and frame passes get their shader modules and pipelines: the
// renderer's caches.
struct PipelineCaches {
  ModuleCache& modules;
  PipelineCache& pipelines;
};

}  // namespace spire::engine

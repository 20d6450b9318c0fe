#include "renderer/frame_pass.h"

#include <fmt/format.h>

#include <array>

#include "renderer/texture_bake.h"
#include "renderer/world_roles.h"

namespace spire::engine {

namespace {

struct PassKind {
  WorldRole vertex;
  WorldRole fragment;
  bool screen;  // sized and culled like the frame; otherwise UV space, both faces
};

constexpr std::array kPassKinds = {
    PassKind{WorldRole::ScreenPassVertex, WorldRole::ScreenPassFragment, true},
    PassKind{WorldRole::ObjectPassVertex, WorldRole::ObjectPassFragment, false},
};

}  // namespace

// Builds one pass; a class so that each step is a function of its own.
class FramePassBuilder {
 public:
  FramePassBuilder(const vk::Context& ctx, PipelineCaches caches, const PassKind& kind,
                   const FramePassSettings& settings)
      : ctx_(ctx), caches_(caches), kind_(kind), settings_(settings) {}

  Expected<std::unique_ptr<FramePass>> build(const KernelProgram& vertex, const KernelProgram& fragment,
                                             const BindingSources& sources) {
    auto pass = std::make_unique<FramePass>();
    pass->mesh_ = sources.mesh;
    pass->objectSpace_ = !kind_.screen;
    auto targets = targetsOf(fragment);
    if (!targets) return targets.error();
    pass->extent_ = kind_.screen ? VkExtent2D{std::max(1U, (settings_.screen.width + 1) / 2),
                                              std::max(1U, (settings_.screen.height + 1) / 2)}
                                 : VkExtent2D{targets->size, targets->size};
    BindingSources passSources = sources;
    passSources.fragmentExtent = pass->extent_;
    for (const KernelProgram* kernel : {&vertex, &fragment}) {
      auto bound = bindKernel(ctx_, *kernel, passSources);
      if (!bound) return bound.error();
      pass->kernels_.push_back(std::move(bound).value());
    }
    const BoundKernel* kernels[] = {&pass->kernels_[0], &pass->kernels_[1]};
    auto descriptors = createDescriptors(ctx_, kernels);
    if (!descriptors) return descriptors.error();
    pass->descriptors_ = std::move(descriptors).value();
    auto vertexInput = vertexInputs(vertex, sources);
    if (!vertexInput) return vertexInput.error();
    pass->vertexInputs_ = std::move(vertexInput).value();
    if (auto pipeline = buildPipeline(*pass, vertex, fragment, targets->targets); !pipeline) return pipeline.error();
    if (auto images = createImages(*pass, targets->targets); !images) return images.error();
    return pass;
  }

 private:
  Expected<BakeTargets> targetsOf(const KernelProgram& fragment) const {
    TextureBakeOptions options;
    options.defaultSize = settings_.objectTextureSize;
    return collectBakeTargets(ctx_, fragment, options);
  }

  Expected<void> buildPipeline(FramePass& pass, const KernelProgram& vertex, const KernelProgram& fragment,
                               const std::vector<BakeTarget>& targets) {
    auto vertexModule = caches_.modules.get(ctx_, vertex.hash, vertex.spirv);
    if (!vertexModule) return vertexModule.error();
    auto fragmentModule = caches_.modules.get(ctx_, fragment.hash, fragment.spirv);
    if (!fragmentModule) return fragmentModule.error();
    vk::GraphicsPipelineBuilder builder;
    builder.vertexShader(*vertexModule).fragmentShader(*fragmentModule);
    pass.vertexInputs_.applyTo(builder);
    for (const BakeTarget& target : targets) builder.colorFormat(target.format);
    builder.depthFormat(VK_FORMAT_D32_SFLOAT).descriptorSetLayouts(pass.descriptors_.layoutHandles());
    const bool cull = kind_.screen && !settings_.doubleSided;
    builder.cullMode(cull ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    auto pipeline = caches_.pipelines.get(ctx_, builder, vertex.hash + " " + fragment.hash, pass.descriptors_);
    if (!pipeline) return pipeline.error();
    pass.pipeline_ = std::move(pipeline).value();
    return {};
  }

  Expected<void> createImages(FramePass& pass, const std::vector<BakeTarget>& targets) {
    const auto [width, height] = pass.extent_;
    for (const BakeTarget& target : targets) {
      auto image = vk::Image::create(
          ctx_, {width, height, target.format, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
      if (!image) return Error::fromVk(image.error());
      pass.targets_.push_back(std::move(image).value());
    }
    auto depth =
        vk::Image::create(ctx_, {width, height, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    if (!depth) return Error::fromVk(depth.error());
    pass.depth_ = std::make_unique<vk::Image>(std::move(depth).value());
    auto sampler = vk::createSampler(ctx_, vk::SamplerDesc{});
    if (!sampler) return Error::fromVk(sampler.error());
    pass.sampler_ = std::move(sampler).value();
    for (size_t i = 0; i < targets.size(); ++i) {
      pass.textures_[targets[i].component] = SampledTexture{pass.targets_[i].view(), pass.sampler_.get()};
    }
    return {};
  }

  const vk::Context& ctx_;
  PipelineCaches caches_;
  const PassKind& kind_;
  const FramePassSettings& settings_;
};

void FramePass::updateFrameValues(const FrameState& frame, const glm::mat4& model) const {
  for (const BoundKernel& kernel : kernels_) writeFrameValues(kernel, frame, model);
}

void FramePass::record(const vk::Context& ctx, VkCommandBuffer cmd) {
  std::vector<vk::ColorTarget> colors;
  for (vk::Image& image : targets_) {
    image.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    colors.push_back({image.view(), {}});
  }
  depth_->transition(cmd, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
  vk::beginRendering(ctx, cmd, extent_, colors, vk::DepthTarget{depth_->view(), 1.0F});
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_->pipeline.get());
  bindDescriptors(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_->layout.get(), descriptors_);
  vertexInputs_.bind(cmd);
  vkCmdBindIndexBuffer(cmd, mesh_->indices.handle(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, mesh_->indexCount(), 1, 0, 0, 0);
  vk::endRendering(ctx, cmd);
  for (vk::Image& image : targets_) image.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

Expected<std::vector<std::unique_ptr<FramePass>>> createFramePasses(const vk::Context& ctx, PipelineCaches caches,
                                                                    const VariantProgram& program,
                                                                    const BindingSources& sources,
                                                                    const FramePassSettings& settings) {
  std::vector<std::unique_ptr<FramePass>> passes;
  for (const PassKind& kind : kPassKinds) {
    // A vertex kernel alone (it positions the pass) renders nothing anyone reads.
    const KernelProgram* fragment = program.kernelWithRole(kind.fragment);
    if (!fragment) continue;
    const KernelProgram* vertex = program.kernelWithRole(kind.vertex);
    if (!vertex) {
      return Error{
          fmt::format("'{}' has a {} kernel but no vertex kernel for its pass", program.shader, fragment->world),
          {},
          {}};
    }
    auto pass = FramePassBuilder(ctx, caches, kind, settings).build(*vertex, *fragment, sources);
    if (!pass) return pass.error();
    passes.push_back(std::move(pass).value());
  }
  return passes;
}

}  // namespace spire::engine

#include "renderer/draw_item.h"

#include <fmt/format.h>

#include "renderer/world_roles.h"

namespace spire::engine {

Expected<std::vector<std::string>> fragmentOutputs(const KernelProgram& fragment) {
  std::vector<std::string> outputs;
  for (const KernelOutput& output : fragment.outputs) {
    if (output.kind != OutputKind::Varying) continue;
    if (output.location >= outputs.size()) outputs.resize(output.location + 1);
    outputs[output.location] = output.component;
  }
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].empty()) {
      return Error{fmt::format("the {} kernel writes no color at location {}", fragment.world, i), {}, {}};
    }
  }
  if (outputs.empty()) return Error{fmt::format("the {} kernel writes no color", fragment.world), {}, {}};
  return outputs;
}

namespace {

// A draw of one object whose kernels sample texture bakes as arrays
// (instanced pipelines) gets arrays of one layer, its own bakes.
Expected<void> addBakeArrays(const vk::Context& ctx, const KernelProgram& vertex, const KernelProgram& fragment,
                             BindingSources& sources, DrawItem& item) {
  if (sources.textureArrays || !(readsBakeArrays(vertex) || readsBakeArrays(fragment))) return {};
  const KernelProgram* kernels[] = {&vertex, &fragment};
  const TextureBakeResult* layers[] = {sources.textureBake};
  auto arrays = buildBakeArrays(ctx, kernels, layers);
  if (!arrays) return arrays.error();
  item.bakeArrays = std::make_unique<BakeArrays>(std::move(arrays).value());
  sources.textureArrays = &item.bakeArrays->textures;
  return {};
}

Expected<SharedPipeline> buildPipeline(const vk::Context& ctx, PipelineCaches caches, const KernelProgram& vertex,
                                       const KernelProgram& fragment, const DrawItem& item,
                                       const DrawPlacement& placement, const TargetFormats& formats, bool overlay) {
  auto vertexModule = caches.modules.get(ctx, vertex.hash, vertex.spirv);
  if (!vertexModule) return vertexModule.error();
  auto fragmentModule = caches.modules.get(ctx, fragment.hash, fragment.spirv);
  if (!fragmentModule) return fragmentModule.error();
  vk::GraphicsPipelineBuilder builder;
  builder.vertexShader(*vertexModule).fragmentShader(*fragmentModule);
  item.vertexInputs.applyTo(builder);
  for (VkFormat format : formats.colors) builder.colorFormat(format);
  if (overlay) {
    builder.depthFormat(formats.depth, false, VK_COMPARE_OP_LESS_OR_EQUAL).alphaBlend();
  } else {
    builder.depthFormat(formats.depth);
  }
  builder.descriptorSetLayouts(item.descriptors.layoutHandles());
  // Meshes are wound counter-clockwise seen from the front, and the
  // projection's y flip keeps that winding on screen.
  builder.cullMode(placement.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT, VK_FRONT_FACE_COUNTER_CLOCKWISE);
  return caches.pipelines.get(ctx, builder, vertex.hash + " " + fragment.hash, item.descriptors);
}

}  // namespace

Expected<DrawItem> createDrawItem(const vk::Context& ctx, PipelineCaches caches, const VariantProgram& program,
                                  const BindingSources& sources, const DrawPlacement& placement,
                                  const TargetFormats& formats) {
  const KernelProgram* vertex = program.kernelWithRole(WorldRole::VertexStage);
  const KernelProgram* fragment = program.kernelWithRole(WorldRole::FragmentStage);
  if (!vertex || !fragment) {
    return Error{
        fmt::format("'{}' has no {} kernel to draw with", program.shader, vertex ? "fragment" : "vertex"), {}, {}};
  }
  auto outputs = fragmentOutputs(*fragment);
  if (!outputs) return outputs.error();
  if (outputs->size() != formats.colors.size()) {
    return Error{fmt::format("'{}' writes {} colors, but the frame has {} color targets", program.shader,
                             outputs->size(), formats.colors.size()),
                 {},
                 {}};
  }

  DrawItem item;
  item.mesh = sources.mesh;
  item.model = placement.model;
  auto passes = createFramePasses(ctx, caches, program, sources,
                                  {.screen = placement.screen, .doubleSided = placement.doubleSided});
  if (!passes) return passes.error();
  item.passes = std::move(passes).value();
  PassTextures passTextures;
  for (const auto& pass : item.passes) passTextures.insert(pass->textures().begin(), pass->textures().end());
  BindingSources drawSources = sources;
  drawSources.passTextures = &passTextures;
  drawSources.instanceCapacity = placement.instanceCapacity;
  drawSources.fragmentExtent = placement.screen;
  if (placement.textureArrays) drawSources.textureArrays = placement.textureArrays;
  if (auto arrays = addBakeArrays(ctx, *vertex, *fragment, drawSources, item); !arrays) return arrays.error();
  for (const KernelProgram* kernel : {vertex, fragment}) {
    auto bound = bindKernel(ctx, *kernel, drawSources);
    if (!bound) return bound.error();
    item.kernels.push_back(std::move(bound).value());
  }
  const BoundKernel* kernels[] = {&item.kernels[0], &item.kernels[1]};
  auto descriptors = createDescriptors(ctx, kernels);
  if (!descriptors) return descriptors.error();
  item.descriptors = std::move(descriptors).value();

  auto vertexInput = vertexInputs(*vertex, sources);
  if (!vertexInput) return vertexInput.error();
  item.vertexInputs = std::move(vertexInput).value();
  auto pipeline = buildPipeline(ctx, caches, *vertex, *fragment, item, placement, formats, false);
  if (!pipeline) return pipeline.error();
  item.pipeline = std::move(pipeline).value();
  return item;
}

Expected<SharedPipeline> createOverlayPipeline(const vk::Context& ctx, PipelineCaches caches,
                                               const VariantProgram& program, const DrawItem& item,
                                               const DrawPlacement& placement, const TargetFormats& formats) {
  const KernelProgram* vertex = program.kernelWithRole(WorldRole::VertexStage);
  const KernelProgram* fragment = program.kernelWithRole(WorldRole::FragmentStage);
  if (!vertex || !fragment) return Error{fmt::format("'{}' has no kernels to draw with", program.shader), {}, {}};
  return buildPipeline(ctx, caches, *vertex, *fragment, item, placement, formats, true);
}

void updateFrameValues(const DrawItem& item, const FrameState& frame) {
  for (const BoundKernel& kernel : item.kernels) writeFrameValues(kernel, frame, item.model);
  for (const auto& pass : item.passes) pass->updateFrameValues(frame, item.model);
}

void recordPasses(const vk::Context& ctx, VkCommandBuffer cmd, const DrawItem& item, const FrameWork& work) {
  for (const auto& pass : item.passes) {
    if (pass->objectSpace() ? work.objectPasses : work.screenPasses) pass->record(ctx, cmd);
  }
}

void recordDraw(VkCommandBuffer cmd, const DrawItem& item) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, item.pipeline->pipeline.get());
  bindDescriptors(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, item.pipeline->layout.get(), item.descriptors);
  item.vertexInputs.bind(cmd);
  vkCmdBindIndexBuffer(cmd, item.mesh->indices.handle(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, item.mesh->indexCount(), 1, 0, 0, 0);
}

}  // namespace spire::engine

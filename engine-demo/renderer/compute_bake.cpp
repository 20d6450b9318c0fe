#include "renderer/compute_bake.h"

#include <fmt/format.h>

#include "renderer/pipeline_descriptors.h"
#include "renderer/surface_samples.h"
#include "vk/timer.h"

namespace spire::engine {

namespace {

// bufferExport kernels use 64 invocations per workgroup (docs/reflection.md).
constexpr uint32_t kWorkgroupSize = 64;

// Samples over a mesh's surface for a uniform bake: enough that a material's
// texture-scale detail averages out, few enough to cost little at load.
constexpr uint32_t kSurfaceSamples = 4096;

struct ComputeOutput {
  BoundKernel bound;
  const Block* layout = nullptr;
  vk::Buffer* records = nullptr;
  SharedPipeline pipeline;
};

Expected<ComputeOutput> dispatch(const vk::Context& ctx, PipelineCaches caches, const KernelProgram& kernel,
                                 const BindingSources& sources, BakeTiming& timing) {
  timing.world = kernel.world;
  auto bound = bindKernel(ctx, kernel, sources);
  if (!bound) return bound.error();
  if (bound->outputs.size() != 1) {
    return Error{fmt::format("the {} kernel must write exactly one record buffer (bufferExport), it writes {}",
                             kernel.world, bound->outputs.size()),
                 {},
                 {}};
  }
  const auto [slot, records] = *bound->outputs.begin();
  const Block* layout = kernel.block(slot);
  const BoundKernel* kernels[] = {&*bound};
  auto descriptors = createDescriptors(ctx, kernels);
  if (!descriptors) return descriptors.error();
  auto module = caches.modules.get(ctx, kernel.hash, kernel.spirv);
  if (!module) return module.error();
  auto pipeline = caches.pipelines.getCompute(ctx, *module, kernel.hash, *descriptors);
  if (!pipeline) return pipeline.error();

  const auto invocations = static_cast<uint32_t>(sources.recordVertices()->size());
  const uint32_t groups = (invocations + kWorkgroupSize - 1) / kWorkgroupSize;
  const vk::HostTimer timer;
  auto submitted = ctx.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, (*pipeline)->pipeline.get());
    bindDescriptors(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, (*pipeline)->layout.get(), *descriptors);
    vkCmdDispatch(cmd, groups, 1, 1);
    VkMemoryBarrier toHost{};
    toHost.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    toHost.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                         nullptr, 0, nullptr);
  });
  timing.milliseconds = timer.elapsedMs();
  if (!submitted) return Error::fromVk(submitted.error());
  return ComputeOutput{std::move(bound).value(), layout, records, std::move(pipeline).value()};
}

}  // namespace

Expected<UniformBakeResult> runUniformBake(const vk::Context& ctx, PipelineCaches caches, const KernelProgram& kernel,
                                           const BindingSources& sources, BakeTiming& timing) {
  // The kernel runs once per surface sample, which it reads as a vertex.
  const SurfaceSamples samples = sampleSurface(sources.mesh->mesh, kSurfaceSamples);
  BindingSources overSamples = sources;
  overSamples.computeVertices = &samples.points;
  auto output = dispatch(ctx, caches, kernel, overSamples, timing);
  if (!output) return output.error();
  const Block& layout = *output->layout;
  const std::span<const std::byte> memory(static_cast<const std::byte*>(output->records->mapped()),
                                          static_cast<size_t>(output->records->size()));
  UniformBakeResult result;
  result.pipeline = output->pipeline;
  for (const BlockMember& member : layout.members) {
    if (!member.type.isNumeric()) {
      return Error{
          fmt::format("cannot average '{}' of type {} over the surface", member.component, member.type.name), {}, {}};
    }
    std::vector<double> sum(member.type.componentCount(), 0.0);
    for (size_t i = 0; i < samples.weights.size(); ++i) {
      const auto values = readValue(memory.subspan(i * layout.recordStride, layout.recordStride), member);
      for (size_t c = 0; c < values.size(); ++c) sum[c] += samples.weights[i] * values[c];
    }
    result.values[member.component] = std::move(sum);
  }
  return result;
}

Expected<VertexBakeResult> runVertexBake(const vk::Context& ctx, PipelineCaches caches, const KernelProgram& kernel,
                                         const BindingSources& sources, BakeTiming& timing) {
  auto output = dispatch(ctx, caches, kernel, sources, timing);
  if (!output) return output.error();
  // Keep the record buffer; the rest of the kernel's bindings die here.
  for (auto& buffer : output->bound.buffers) {
    if (buffer.get() == output->records) return VertexBakeResult{std::move(buffer), *output->layout, output->pipeline};
  }
  return Error{fmt::format("the {} kernel's record buffer was lost", kernel.world), {}, {}};
}

}  // namespace spire::engine

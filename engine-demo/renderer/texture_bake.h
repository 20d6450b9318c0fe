// The PrebakeTex bake, run once at load: the mesh is rasterized in UV space
// (each vertex at clip position uv * 2 - 1) with the kernel as fragment
// shader, one render target per exported component. Texels no triangle covers
// are then filled from covered neighbours (dilation), so bilinear lookups at
// chart borders do not blend in the clear color.
#pragma once

#include "renderer/compute_bake.h"
#include "renderer/kernel_bindings.h"
#include "renderer/pipeline_cache.h"

namespace spire::engine {

struct TextureBakeOptions {
  uint32_t defaultSize = 1024;                             // when an output has no TextureSize hint
  VkFormat defaultFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // when it has no Format hint
  // Bake every output in this format whatever its hint says (data-layout
  // analysis bakes in RGBA32F), and keep the texels on the CPU.
  std::optional<VkFormat> forceFormat;
  uint32_t dilationTexels = 4;
};

// The Vulkan format of a `Format` hint: "R8", "RG8", "RGBA8", "RGB10_A2"
// (unsigned normalized), "R16F", "RG16F", "RGBA16F", "R32F", "RGBA32F";
// nullopt for names the engine does not support.
std::optional<VkFormat> bakeFormat(std::string_view hint);
// The hint names, for messages.
std::string bakeFormatNames();

// The render targets of a kernel that renders into textures (the texture
// bake, the per-frame passes): one per color output, in location order, in
// the format and size its hints ask for, else `options`' defaults. One render
// pass has one extent, so they share the largest size any output asks for.
struct BakeTarget {
  std::string component;
  uint32_t location = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
};
struct BakeTargets {
  std::vector<BakeTarget> targets;
  uint32_t size = 0;
};
// More targets than the device renders in one pass (maxColorAttachments) is
// an error naming the kernel: every output of a kernel goes to one pass.
Expected<BakeTargets> collectBakeTargets(const vk::Context& ctx, const KernelProgram& kernel,
                                         const TextureBakeOptions& options);

// Pipelines come from `caches` and stay with the result.
Expected<TextureBakeResult> runTextureBake(const vk::Context& ctx, PipelineCaches caches, const KernelProgram& kernel,
                                           const BindingSources& sources, const TextureBakeOptions& options,
                                           BakeTiming& timing);

}  // namespace spire::engine

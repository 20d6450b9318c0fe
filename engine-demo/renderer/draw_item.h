// One mesh instance ready to draw every frame: the variant's Vertex and
// Fragment kernels as a graphics pipeline, their descriptor sets, and the
// buffers behind it (per-frame values are rewritten before each frame).
#pragma once

#include <glm/mat4x4.hpp>

#include <memory>

#include "renderer/bake_arrays.h"
#include "renderer/frame_pass.h"
#include "renderer/kernel_bindings.h"
#include "renderer/module_cache.h"
#include "renderer/pipeline_cache.h"
#include "renderer/pipeline_descriptors.h"
#include "renderer/vertex_inputs.h"
#include "vk/pipeline.h"

namespace spire::engine {

// Formats of the frame's render target, which every pipeline must match.
struct TargetFormats {
  std::vector<VkFormat> colors;  // by Fragment output location
  VkFormat depth = VK_FORMAT_D32_SFLOAT;
};

// Where and how an instance draws its mesh.
struct DrawPlacement {
  glm::mat4 model{1.0F};
  bool doubleSided = false;  // otherwise back faces (clockwise on screen) are culled
  VkExtent2D screen{};       // the frame's resolution, which sizes a multi-rate pass
  // Records of each per-instance block (instanceImport): the most instances
  // one draw of this item renders.
  uint32_t instanceCapacity = 1;
  // Texture bakes as arrays with one layer per object the item draws
  // (bake_arrays.h); null: the item's own bakes, as arrays of one layer.
  const PassTextures* textureArrays = nullptr;
};

struct DrawItem {
  const GpuMesh* mesh = nullptr;
  glm::mat4 model{1.0F};
  std::vector<BoundKernel> kernels;
  DescriptorBundle descriptors;
  VertexInputs vertexInputs;  // the mesh, and the vertex bake's records when Vertex reads them as inputs
  SharedPipeline pipeline;    // shared with other draws of the same kernels and state (pipeline_cache.h)
  std::vector<std::unique_ptr<FramePass>> passes;  // rendered before the draw, every frame
  std::unique_ptr<BakeArrays> bakeArrays;          // the object's texture bakes as one-layer arrays, when sampled so
};

// The Fragment kernel's color outputs by location (location 0 is the image
// the demo measures), or an error when they are not 0..n-1.
Expected<std::vector<std::string>> fragmentOutputs(const KernelProgram& fragment);

Expected<DrawItem> createDrawItem(const vk::Context& ctx, PipelineCaches caches, const VariantProgram& program,
                                  const BindingSources& sources, const DrawPlacement& placement,
                                  const TargetFormats& formats);

// The item's pipeline again, over the same descriptor set layouts, blended
// by alpha and depth-tested LESS_OR_EQUAL without writing depth: a second
// draw of the same surfaces over the first (level-of-detail cross-fades).
Expected<SharedPipeline> createOverlayPipeline(const vk::Context& ctx, PipelineCaches caches,
                                               const VariantProgram& program, const DrawItem& item,
                                               const DrawPlacement& placement, const TargetFormats& formats);

void updateFrameValues(const DrawItem& item, const FrameState& frame);
// Which of a frame's work one submission records: a stereo frame renders
// shared object-space passes once, then each eye's screen passes and draw.
struct FrameWork {
  bool screenPasses = true;
  bool objectPasses = true;
  bool draw = true;
};

// The item's frame passes that `work` selects, outside the frame's render
// pass and before it.
void recordPasses(const vk::Context& ctx, VkCommandBuffer cmd, const DrawItem& item, const FrameWork& work);
void recordDraw(VkCommandBuffer cmd, const DrawItem& item);

}  // namespace spire::engine

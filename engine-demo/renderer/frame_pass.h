// Per-frame passes (paper section 7.3): before an instance's draw, the engine
// renders its mesh with a pair of the variant's kernels into textures that
// the draw's Fragment kernel then samples. The multi-rate and object-space
// pipelines have the same topology; their worlds' roles say which pass runs:
//
// - screen (lowResVertex, lowResFragment): the mesh from the camera at half
//   the width and height, a quarter of the pixels; Fragment fetches the
//   results by screen position (screenTextureImport).
// - object (objectSpaceVertex, objectSpaceFragment): the mesh in its UV
//   space (its vertex kernel places each vertex at its UV); Fragment fetches
//   at vert_uv (textureImport).
//
// Unlike the texture bake, both run every frame, so they may read per-frame
// values. One target per output of the fragment kernel, in its Format hint
// (else RGBA16F); object-space targets are TextureSize texels square.
#pragma once

#include <memory>
#include <vector>

#include "renderer/kernel_bindings.h"
#include "renderer/pipeline_cache.h"
#include "renderer/pipeline_descriptors.h"
#include "renderer/vertex_inputs.h"

namespace spire::engine {

struct FramePassSettings {
  VkExtent2D screen{};               // the frame's full resolution
  bool doubleSided = false;          // the instance's culling, for the screen pass
  uint32_t objectTextureSize = 512;  // object-space targets without a TextureSize hint
};

class FramePass {
 public:
  // The world of the pass's fragment kernel, for messages and reports.
  const std::string& world() const { return kernels_.back().world; }
  VkExtent2D extent() const { return extent_; }
  // Rendered in UV space, so independent of where the camera's eye is: a
  // stereo frame may run it once for both eyes.
  bool objectSpace() const { return objectSpace_; }
  // What the draw's Fragment kernel samples, by component.
  const PassTextures& textures() const { return textures_; }

  void updateFrameValues(const FrameState& frame, const glm::mat4& model) const;
  // Renders into the targets and leaves them ready to sample. Outside a
  // render pass, before the draw that samples them.
  void record(const vk::Context& ctx, VkCommandBuffer cmd);

 private:
  friend class FramePassBuilder;
  const GpuMesh* mesh_ = nullptr;
  VkExtent2D extent_{};
  bool objectSpace_ = false;
  std::vector<BoundKernel> kernels_;  // vertex, fragment
  DescriptorBundle descriptors_;
  VertexInputs vertexInputs_;
  SharedPipeline pipeline_;
  std::vector<vk::Image> targets_;
  std::unique_ptr<vk::Image> depth_;
  vk::Sampler sampler_;
  PassTextures textures_;
};

// The passes `program` has, in the order they run: one per pass role whose
// fragment kernel the variant has, with the vertex kernel of the same pass.
Expected<std::vector<std::unique_ptr<FramePass>>> createFramePasses(const vk::Context& ctx, PipelineCaches caches,
                                                                    const VariantProgram& program,
                                                                    const BindingSources& sources,
                                                                    const FramePassSettings& settings);

}  // namespace spire::engine

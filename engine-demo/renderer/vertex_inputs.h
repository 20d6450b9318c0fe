// Where a rasterized kernel's `in` variables come from (standardImport into
// a vertex or texture-bake kernel): mesh attributes from the mesh's vertex
// buffer, and values of a vertex bake from its record buffer, bound as a
// second vertex buffer with the producer's record as the vertex (the paper's
// Figure 4 draws PrebakeVertex -> Vertex and PrebakeVertex -> PrebakeTex this
// way). One description serves the pipeline (its vertex input state) and the
// draw (which buffers to bind), so the two cannot disagree.
#pragma once

#include <vector>

#include "renderer/kernel_bindings.h"
#include "vk/pipeline.h"

namespace spire::engine {

struct VertexInputs {
  struct Binding {
    uint32_t binding = 0;
    uint32_t stride = 0;
    VkBuffer buffer = VK_NULL_HANDLE;
  };
  struct Attribute {
    uint32_t location = 0;
    uint32_t binding = 0;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t offset = 0;
  };
  std::vector<Binding> bindings;  // binding 0 is always the mesh
  std::vector<Attribute> attributes;

  // A mesh attribute at `location` in addition to the kernel's own (the
  // texture bake's UV, read by the engine's vertex shader).
  void addMeshAttribute(uint32_t location, VkFormat format, uint32_t offset);
  void applyTo(vk::GraphicsPipelineBuilder& builder) const;
  void bind(VkCommandBuffer cmd) const;
};

// The vertex inputs of `kernel`'s Varying inputs from the mesh and vertex
// bake roles; any other source is an error naming the kernel and the input.
Expected<VertexInputs> vertexInputs(const KernelProgram& kernel, const BindingSources& sources);

}  // namespace spire::engine

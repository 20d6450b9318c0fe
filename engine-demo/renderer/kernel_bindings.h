// Feeding one kernel: every descriptor binding its reflection names, filled
// from where the value's world says it comes from (world_roles.h): material
// values, per-frame values, mesh vertices as storage records, the results of
// the bakes that ran before it, and the textures of the frame's passes. The same code binds bake kernels and the
// kernels of each frame's draw.
#pragma once

#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "renderer/gpu_resources.h"
#include "renderer/hazard_records.h"
#include "renderer/supplied_values.h"
#include "renderer/value_layout.h"
#include "renderer/variant_program.h"
#include "vk/pipeline.h"

namespace spire::engine {

// The value an input of MaterialUniform (or an overridden FrameUniform) gets.
struct MaterialValue {
  std::vector<double> numbers;
  const GpuTexture* texture = nullptr;
  std::string identity;     // stable text naming the value, for bake cache keys
  std::string engineValue;  // set: the per-frame engine value of that name (frameValue), written every frame
};
using MaterialValues = std::map<std::string, MaterialValue, std::less<>>;

struct BakedTexture {
  vk::Image image;
  vk::Sampler sampler;
  std::vector<std::byte> texels;  // the baked texels as stored, when TextureBakeOptions::forceFormat asked to keep them
};

// Each bake result below keeps the pipeline it was made with: the
// renderer's pipeline caches hold pipelines only while something uses them,
// and the same kernel baked on other meshes (a terrain's tiles, every object
// type of a level) then reuses it instead of having lavapipe compile it
// again.
struct UniformBakeResult {
  std::map<std::string, std::vector<double>, std::less<>> values;  // component -> average over the surface
  std::shared_ptr<const vk::Pipeline> pipeline;
};

struct VertexBakeResult {
  std::unique_ptr<vk::Buffer> buffer;  // one record per vertex
  Block layout;                        // the producer's record layout
  std::shared_ptr<const vk::Pipeline> pipeline;
};

struct TextureBakeResult {
  std::map<std::string, BakedTexture, std::less<>> textures;  // component -> its texture
  uint32_t size = 0;                                          // width and height of every texture
  std::vector<uint8_t> coverage;                              // 1 for texels a triangle covered (before dilation)
  std::shared_ptr<const vk::Pipeline> pipeline;
};

// A texture rendered earlier in the frame by a per-frame pass
// (frame_pass.h), ready for a combined image sampler.
struct SampledTexture {
  VkImageView view = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
};
using PassTextures = std::map<std::string, SampledTexture, std::less<>>;  // by component

struct BindingSources {
  const GpuMesh* mesh = nullptr;
  const MaterialValues* material = nullptr;
  const UniformBakeResult* uniformBake = nullptr;
  const VertexBakeResult* vertexBake = nullptr;
  const TextureBakeResult* textureBake = nullptr;
  const PassTextures* passTextures = nullptr;  // the frame passes' results, when the kernel samples them
  // Texture-bake results as texture arrays (bake_arrays.h), by component,
  // for kernels that sample them as sampler2DArray (textureArrayImport).
  const PassTextures* textureArrays = nullptr;
  // Records of each per-instance storage block (instanceImport): 1 for a
  // draw of one object, the batch's size for an instanced draw.
  uint32_t instanceCapacity = 1;
  // Instrumented kernels (hazard_records.h): who reads their records, and
  // the size of the target a fragment kernel renders to. Without a
  // collector, an instrumented kernel records into a buffer nobody reads.
  HazardCollector* hazards = nullptr;
  VkExtent2D fragmentExtent{};
  // The vertices a compute kernel reads as records, one invocation each,
  // when they are not the mesh's own: a uniform bake runs over samples of
  // the mesh's surface (surface_samples.h).
  const std::vector<scene::Vertex>* computeVertices = nullptr;

  // The vertices compute kernels run over; null without a mesh.
  const std::vector<scene::Vertex>* recordVertices() const {
    return computeVertices ? computeVertices : mesh ? &mesh->mesh.vertices : nullptr;
  }
};

// One member of a per-instance record and where its value comes from.
struct InstanceField {
  BlockMember member;
  std::string component;
  bool baked = false;  // the object's uniform-bake average; otherwise an instance value (instanceValue)
};

// A storage block read at gl_InstanceIndex: `capacity` records of `stride`
// bytes, rewritten by whoever draws the instances.
struct InstanceBlock {
  vk::Buffer* buffer = nullptr;
  uint32_t stride = 0;
  uint32_t capacity = 0;
  std::vector<InstanceField> fields;
};

// Writes record `index` of `block`: its instance values from `instance`,
// and, when `bake` is given, its baked values from `bake` (which must hold
// them: bindKernel checked the bound object's).
void writeInstanceRecord(const InstanceBlock& block, uint32_t index, const InstanceState& instance,
                         const UniformBakeResult* bake);

// A uniform-block member refreshed every frame from FrameState.
struct FrameWrite {
  vk::Buffer* buffer = nullptr;
  BlockMember member;
  std::string component;
};

// One descriptor a kernel binds: where, of which type, and the resource.
struct BoundDescriptor {
  DescriptorSlot slot;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  VkBuffer buffer = VK_NULL_HANDLE;   // uniform and storage buffers
  VkImageView view = VK_NULL_HANDLE;  // combined image samplers
  VkSampler sampler = VK_NULL_HANDLE;
  std::string what;  // names the resource in messages: "uniform block 'spire_FrameUniform'"

  bool sameResource(const BoundDescriptor& other) const {
    return buffer == other.buffer && view == other.view && sampler == other.sampler;
  }
};

// A kernel's buffers and descriptors; createDescriptors
// (pipeline_descriptors.h) turns the descriptors of a pipeline's kernels into
// its descriptor sets.
struct BoundKernel {
  std::string world;
  VkShaderStageFlags stage = 0;
  std::vector<BoundDescriptor> descriptors;
  std::vector<std::unique_ptr<vk::Buffer>> buffers;
  std::vector<FrameWrite> frameWrites;
  std::map<DescriptorSlot, vk::Buffer*> outputs;  // storage blocks the kernel writes
  std::vector<InstanceBlock> instanceBlocks;      // storage blocks read per instance
};

// Creates and fills the buffers of `kernel`'s bindings. Values are assumed
// resolved (resolveMaterial checked them); a missing one is still an error,
// not a crash.
Expected<BoundKernel> bindKernel(const vk::Context& ctx, const KernelProgram& kernel, const BindingSources& sources);

// Writes this frame's values into the kernel's per-frame uniform members,
// and the instance values of record 0 of its per-instance blocks (a draw of
// one object at `model`).
void writeFrameValues(const BoundKernel& kernel, const FrameState& frame, const glm::mat4& model);

}  // namespace spire::engine

// Shader modules, graphics pipelines for dynamic rendering (no render pass
// objects), compute pipelines, descriptor helpers and the begin/end
// rendering calls that go with them.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vk/context.h"
#include "vk/handle.h"
#include "vk/result.h"

namespace spire::vk {

// SPIR-V words as produced by spire::codegen::compileGlslToSpirv.
Expected<ShaderModule> createShaderModule(const Context& ctx, std::span<const uint32_t> words);

// A pipeline with the layout it was built with (descriptor sets and push
// constants are bound through the layout).
struct Pipeline {
  PipelineLayout layout;
  PipelineHandle pipeline;
};

class GraphicsPipelineBuilder {
 public:
  GraphicsPipelineBuilder& vertexShader(VkShaderModule module, std::string entry = "main");
  GraphicsPipelineBuilder& fragmentShader(VkShaderModule module, std::string entry = "main");
  GraphicsPipelineBuilder& vertexBinding(uint32_t binding, uint32_t stride,
                                         VkVertexInputRate rate = VK_VERTEX_INPUT_RATE_VERTEX);
  GraphicsPipelineBuilder& vertexAttribute(uint32_t location, uint32_t binding, VkFormat format, uint32_t offset);
  GraphicsPipelineBuilder& topology(VkPrimitiveTopology topology);
  GraphicsPipelineBuilder& cullMode(VkCullModeFlags mode, VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE);
  // One color attachment per call, in location order; blending off.
  GraphicsPipelineBuilder& colorFormat(VkFormat format);
  GraphicsPipelineBuilder& depthFormat(VkFormat format, bool write = true, VkCompareOp compare = VK_COMPARE_OP_LESS);
  // Color attachment 0 blended over what is there by the fragment's alpha
  // (the destination's alpha kept); the others are written as they are.
  GraphicsPipelineBuilder& alphaBlend();
  GraphicsPipelineBuilder& pushConstants(VkShaderStageFlags stages, uint32_t offset, uint32_t size);
  // Set layouts in set order: each call appends the next set number.
  GraphicsPipelineBuilder& descriptorSetLayout(VkDescriptorSetLayout layout);
  GraphicsPipelineBuilder& descriptorSetLayouts(std::span<const VkDescriptorSetLayout> layouts);

  // Viewport and scissor are dynamic state: set them per draw (beginRendering
  // does it for the full render area).
  Expected<Pipeline> build(const Context& ctx) const;
  // Everything build() uses except the shader modules and set layouts, as
  // text: builders with the same key, equal modules and identically defined
  // set layouts build interchangeable pipelines, so a cache of pipelines
  // keys on it (with the modules' and layouts' own keys) and picks up any
  // state added here later.
  std::string stateKey() const;

 private:
  struct Stage {
    VkShaderModule module = VK_NULL_HANDLE;
    std::string entry;
  };
  Stage vertex_;
  Stage fragment_;
  std::vector<VkVertexInputBindingDescription> bindings_;
  std::vector<VkVertexInputAttributeDescription> attributes_;
  VkPrimitiveTopology topology_ = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cullMode_ = VK_CULL_MODE_NONE;
  VkFrontFace frontFace_ = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  std::vector<VkFormat> colorFormats_;
  VkFormat depthFormat_ = VK_FORMAT_UNDEFINED;
  bool depthWrite_ = true;
  VkCompareOp depthCompare_ = VK_COMPARE_OP_LESS;
  bool alphaBlend_ = false;
  std::vector<VkPushConstantRange> pushConstants_;
  std::vector<VkDescriptorSetLayout> setLayouts_;
};

Expected<Pipeline> createComputePipeline(const Context& ctx, VkShaderModule module,
                                         std::span<const VkDescriptorSetLayout> setLayouts = {},
                                         std::span<const VkPushConstantRange> pushConstants = {},
                                         const char* entry = "main");

// Pipeline layout on its own, shared by the graphics builder and compute.
Expected<PipelineLayout> createPipelineLayout(const Context& ctx, std::span<const VkDescriptorSetLayout> setLayouts,
                                              std::span<const VkPushConstantRange> pushConstants);

class DescriptorSetLayoutBuilder {
 public:
  DescriptorSetLayoutBuilder& binding(uint32_t binding, VkDescriptorType type, VkShaderStageFlags stages,
                                      uint32_t count = 1);
  Expected<DescriptorSetLayout> build(const Context& ctx) const;

 private:
  std::vector<VkDescriptorSetLayoutBinding> bindings_;
};

Expected<DescriptorPool> createDescriptorPool(const Context& ctx, uint32_t maxSets,
                                              std::span<const VkDescriptorPoolSize> sizes);
// The set lives as long as the pool (freed with it).
Expected<VkDescriptorSet> allocateDescriptorSet(const Context& ctx, VkDescriptorPool pool,
                                                VkDescriptorSetLayout layout);

// Collects descriptor writes for one set and applies them in one call.
class DescriptorWriter {
 public:
  DescriptorWriter& buffer(uint32_t binding, VkDescriptorType type, VkBuffer buffer, VkDeviceSize offset = 0,
                           VkDeviceSize range = VK_WHOLE_SIZE);
  DescriptorWriter& image(uint32_t binding, VkDescriptorType type, VkImageView view, VkSampler sampler,
                          VkImageLayout layout);
  void update(const Context& ctx, VkDescriptorSet set) const;

 private:
  struct Write {
    uint32_t binding;
    VkDescriptorType type;
    std::optional<VkDescriptorBufferInfo> buffer;
    std::optional<VkDescriptorImageInfo> image;
  };
  std::vector<Write> writes_;
};

struct ColorTarget {
  VkImageView view = VK_NULL_HANDLE;
  VkClearColorValue clear{};
};
struct DepthTarget {
  VkImageView view = VK_NULL_HANDLE;
  float clear = 1.0F;
};

// Begins dynamic rendering into images already in COLOR_ATTACHMENT_OPTIMAL /
// DEPTH_STENCIL_ATTACHMENT_OPTIMAL, clearing them and storing the results,
// and sets viewport and scissor to the whole `extent`.
void beginRendering(const Context& ctx, VkCommandBuffer cmd, VkExtent2D extent, std::span<const ColorTarget> colors,
                    const std::optional<DepthTarget>& depth = std::nullopt);
void endRendering(const Context& ctx, VkCommandBuffer cmd);

}  // namespace spire::vk

#include "vk/pipeline.h"

#include <fmt/format.h>

#include <array>

namespace spire::vk {
namespace {

// The fixed-function state of a graphics pipeline, one create-info each. The
// pointers they hold point into the arguments, which must outlive them.

VkPipelineVertexInputStateCreateInfo vertexInputState(std::span<const VkVertexInputBindingDescription> bindings,
                                                      std::span<const VkVertexInputAttributeDescription> attributes) {
  VkPipelineVertexInputStateCreateInfo vertexInput{};
  vertexInput.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  vertexInput.vertexBindingDescriptionCount = static_cast<uint32_t>(bindings.size());
  vertexInput.pVertexBindingDescriptions = bindings.data();
  vertexInput.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
  vertexInput.pVertexAttributeDescriptions = attributes.data();
  return vertexInput;
}

VkPipelineInputAssemblyStateCreateInfo inputAssemblyState(VkPrimitiveTopology topology) {
  VkPipelineInputAssemblyStateCreateInfo inputAssembly{};
  inputAssembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  inputAssembly.topology = topology;
  return inputAssembly;
}

// One viewport and scissor, set per draw as dynamic state.
VkPipelineViewportStateCreateInfo viewportState() {
  VkPipelineViewportStateCreateInfo viewport{};
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  return viewport;
}

VkPipelineRasterizationStateCreateInfo rasterizationState(VkCullModeFlags cullMode, VkFrontFace frontFace) {
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = cullMode;
  raster.frontFace = frontFace;
  raster.lineWidth = 1.0F;
  return raster;
}

VkPipelineMultisampleStateCreateInfo multisampleState() {
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  return multisample;
}

// Without a depth format the pipeline neither tests nor writes depth.
VkPipelineDepthStencilStateCreateInfo depthStencilState(VkFormat format, bool write, VkCompareOp compare) {
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = format != VK_FORMAT_UNDEFINED ? VK_TRUE : VK_FALSE;
  depth.depthWriteEnable = format != VK_FORMAT_UNDEFINED && write ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = compare;
  return depth;
}

VkPipelineColorBlendStateCreateInfo colorBlendState(std::span<const VkPipelineColorBlendAttachmentState> attachments) {
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = static_cast<uint32_t>(attachments.size());
  blend.pAttachments = attachments.data();
  return blend;
}

VkPipelineDynamicStateCreateInfo dynamicState(std::span<const VkDynamicState> states) {
  VkPipelineDynamicStateCreateInfo dynamic{};
  dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dynamic.dynamicStateCount = static_cast<uint32_t>(states.size());
  dynamic.pDynamicStates = states.data();
  return dynamic;
}

}  // namespace

Expected<ShaderModule> createShaderModule(const Context& ctx, std::span<const uint32_t> words) {
  // 0x07230203: the SPIR-V magic number. Checked here because drivers are
  // allowed to crash on garbage, and shader words may come from user files.
  if (words.size() < 5 || words[0] != 0x07230203U) {
    return VkError{VK_ERROR_INVALID_SHADER_NV, "createShaderModule", "not a SPIR-V module"};
  }
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = words.size_bytes();
  info.pCode = words.data();
  VkShaderModule raw = VK_NULL_HANDLE;
  if (auto result = vkCreateShaderModule(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreateShaderModule", {}};
  }
  return makeDeviceHandle<VkShaderModule, vkDestroyShaderModule>(ctx.device(), raw);
}

Expected<PipelineLayout> createPipelineLayout(const Context& ctx, std::span<const VkDescriptorSetLayout> setLayouts,
                                              std::span<const VkPushConstantRange> pushConstants) {
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.setLayoutCount = static_cast<uint32_t>(setLayouts.size());
  info.pSetLayouts = setLayouts.data();
  info.pushConstantRangeCount = static_cast<uint32_t>(pushConstants.size());
  info.pPushConstantRanges = pushConstants.data();
  VkPipelineLayout raw = VK_NULL_HANDLE;
  if (auto result = vkCreatePipelineLayout(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreatePipelineLayout", {}};
  }
  return makeDeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>(ctx.device(), raw);
}

GraphicsPipelineBuilder& GraphicsPipelineBuilder::vertexShader(VkShaderModule module, std::string entry) {
  vertex_ = {module, std::move(entry)};
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::fragmentShader(VkShaderModule module, std::string entry) {
  fragment_ = {module, std::move(entry)};
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::vertexBinding(uint32_t binding, uint32_t stride,
                                                                VkVertexInputRate rate) {
  bindings_.push_back({binding, stride, rate});
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::vertexAttribute(uint32_t location, uint32_t binding, VkFormat format,
                                                                  uint32_t offset) {
  attributes_.push_back({location, binding, format, offset});
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::topology(VkPrimitiveTopology topology) {
  topology_ = topology;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::cullMode(VkCullModeFlags mode, VkFrontFace frontFace) {
  cullMode_ = mode;
  frontFace_ = frontFace;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::colorFormat(VkFormat format) {
  colorFormats_.push_back(format);
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::depthFormat(VkFormat format, bool write, VkCompareOp compare) {
  depthFormat_ = format;
  depthWrite_ = write;
  depthCompare_ = compare;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::alphaBlend() {
  alphaBlend_ = true;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::pushConstants(VkShaderStageFlags stages, uint32_t offset,
                                                                uint32_t size) {
  pushConstants_.push_back({stages, offset, size});
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::descriptorSetLayout(VkDescriptorSetLayout layout) {
  setLayouts_.push_back(layout);
  return *this;
}

GraphicsPipelineBuilder& GraphicsPipelineBuilder::descriptorSetLayouts(std::span<const VkDescriptorSetLayout> layouts) {
  setLayouts_.insert(setLayouts_.end(), layouts.begin(), layouts.end());
  return *this;
}

std::string GraphicsPipelineBuilder::stateKey() const {
  std::string key =
      fmt::format("vs {} fs {}; topology {} cull {} front {}; depth {} write {} compare {}; blend {}", vertex_.entry,
                  fragment_.entry, static_cast<int>(topology_), cullMode_, static_cast<int>(frontFace_),
                  static_cast<int>(depthFormat_), depthWrite_, static_cast<int>(depthCompare_), alphaBlend_);
  for (VkFormat format : colorFormats_) key += fmt::format("; color {}", static_cast<int>(format));
  for (const VkVertexInputBindingDescription& b : bindings_)
    key += fmt::format("; binding {} stride {} rate {}", b.binding, b.stride, static_cast<int>(b.inputRate));
  for (const VkVertexInputAttributeDescription& a : attributes_) {
    key += fmt::format("; attribute {} binding {} format {} offset {}", a.location, a.binding,
                       static_cast<int>(a.format), a.offset);
  }
  for (const VkPushConstantRange& p : pushConstants_)
    key += fmt::format("; push {} {} {}", p.stageFlags, p.offset, p.size);
  key += fmt::format("; {} sets", setLayouts_.size());
  return key;
}

Expected<Pipeline> GraphicsPipelineBuilder::build(const Context& ctx) const {
  if (vertex_.module == VK_NULL_HANDLE || fragment_.module == VK_NULL_HANDLE) {
    return VkError{VK_ERROR_INITIALIZATION_FAILED, "GraphicsPipelineBuilder::build",
                   "vertex and fragment shaders are required"};
  }
  auto layout = createPipelineLayout(ctx, setLayouts_, pushConstants_);
  if (!layout) return layout.error();

  const std::array stages{
      VkPipelineShaderStageCreateInfo{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                                      VK_SHADER_STAGE_VERTEX_BIT, vertex_.module, vertex_.entry.c_str(), nullptr},
      VkPipelineShaderStageCreateInfo{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                                      VK_SHADER_STAGE_FRAGMENT_BIT, fragment_.module, fragment_.entry.c_str(), nullptr},
  };
  const VkPipelineVertexInputStateCreateInfo vertexInput = vertexInputState(bindings_, attributes_);
  const VkPipelineInputAssemblyStateCreateInfo inputAssembly = inputAssemblyState(topology_);
  const VkPipelineViewportStateCreateInfo viewport = viewportState();
  const VkPipelineRasterizationStateCreateInfo raster = rasterizationState(cullMode_, frontFace_);
  const VkPipelineMultisampleStateCreateInfo multisample = multisampleState();
  const VkPipelineDepthStencilStateCreateInfo depth = depthStencilState(depthFormat_, depthWrite_, depthCompare_);
  VkPipelineColorBlendAttachmentState noBlend{};
  noBlend.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  std::vector<VkPipelineColorBlendAttachmentState> blendAttachments(colorFormats_.size(), noBlend);
  if (alphaBlend_ && !blendAttachments.empty()) {
    VkPipelineColorBlendAttachmentState& b = blendAttachments.front();
    b.blendEnable = VK_TRUE;
    b.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    b.colorBlendOp = VK_BLEND_OP_ADD;
    b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    b.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  const VkPipelineColorBlendStateCreateInfo blend = colorBlendState(blendAttachments);
  const std::array dynamicStates{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  const VkPipelineDynamicStateCreateInfo dynamic = dynamicState(dynamicStates);

  // Dynamic rendering: the attachment formats replace the render pass.
  VkPipelineRenderingCreateInfo rendering{};
  rendering.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
  rendering.colorAttachmentCount = static_cast<uint32_t>(colorFormats_.size());
  rendering.pColorAttachmentFormats = colorFormats_.data();
  rendering.depthAttachmentFormat = depthFormat_;

  VkGraphicsPipelineCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  info.pNext = &rendering;
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &inputAssembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout->get();
  VkPipeline raw = VK_NULL_HANDLE;
  if (auto result = vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &raw);
      result != VK_SUCCESS) {
    return VkError{result, "vkCreateGraphicsPipelines", {}};
  }
  return Pipeline{std::move(*layout), makeDeviceHandle<VkPipeline, vkDestroyPipeline>(ctx.device(), raw)};
}

Expected<Pipeline> createComputePipeline(const Context& ctx, VkShaderModule module,
                                         std::span<const VkDescriptorSetLayout> setLayouts,
                                         std::span<const VkPushConstantRange> pushConstants, const char* entry) {
  auto layout = createPipelineLayout(ctx, setLayouts, pushConstants);
  if (!layout) return layout.error();
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                nullptr,
                0,
                VK_SHADER_STAGE_COMPUTE_BIT,
                module,
                entry,
                nullptr};
  info.layout = layout->get();
  VkPipeline raw = VK_NULL_HANDLE;
  if (auto result = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &raw);
      result != VK_SUCCESS) {
    return VkError{result, "vkCreateComputePipelines", {}};
  }
  return Pipeline{std::move(*layout), makeDeviceHandle<VkPipeline, vkDestroyPipeline>(ctx.device(), raw)};
}

DescriptorSetLayoutBuilder& DescriptorSetLayoutBuilder::binding(uint32_t binding, VkDescriptorType type,
                                                                VkShaderStageFlags stages, uint32_t count) {
  bindings_.push_back({binding, type, count, stages, nullptr});
  return *this;
}

Expected<DescriptorSetLayout> DescriptorSetLayoutBuilder::build(const Context& ctx) const {
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = static_cast<uint32_t>(bindings_.size());
  info.pBindings = bindings_.data();
  VkDescriptorSetLayout raw = VK_NULL_HANDLE;
  if (auto result = vkCreateDescriptorSetLayout(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreateDescriptorSetLayout", {}};
  }
  return makeDeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>(ctx.device(), raw);
}

Expected<DescriptorPool> createDescriptorPool(const Context& ctx, uint32_t maxSets,
                                              std::span<const VkDescriptorPoolSize> sizes) {
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.maxSets = maxSets;
  info.poolSizeCount = static_cast<uint32_t>(sizes.size());
  info.pPoolSizes = sizes.data();
  VkDescriptorPool raw = VK_NULL_HANDLE;
  if (auto result = vkCreateDescriptorPool(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreateDescriptorPool", {}};
  }
  return makeDeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>(ctx.device(), raw);
}

Expected<VkDescriptorSet> allocateDescriptorSet(const Context& ctx, VkDescriptorPool pool,
                                                VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  info.descriptorPool = pool;
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (auto result = vkAllocateDescriptorSets(ctx.device(), &info, &set); result != VK_SUCCESS) {
    return VkError{result, "vkAllocateDescriptorSets", {}};
  }
  return set;
}

DescriptorWriter& DescriptorWriter::buffer(uint32_t binding, VkDescriptorType type, VkBuffer buffer,
                                           VkDeviceSize offset, VkDeviceSize range) {
  writes_.push_back({binding, type, VkDescriptorBufferInfo{buffer, offset, range}, std::nullopt});
  return *this;
}

DescriptorWriter& DescriptorWriter::image(uint32_t binding, VkDescriptorType type, VkImageView view, VkSampler sampler,
                                          VkImageLayout layout) {
  writes_.push_back({binding, type, std::nullopt, VkDescriptorImageInfo{sampler, view, layout}});
  return *this;
}

void DescriptorWriter::update(const Context& ctx, VkDescriptorSet set) const {
  // The VkWriteDescriptorSets point into writes_, so they are built only now
  // that writes_ no longer grows (and reallocates).
  std::vector<VkWriteDescriptorSet> writes;
  writes.reserve(writes_.size());
  for (const Write& w : writes_) {
    VkWriteDescriptorSet write{};
    write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    write.dstSet = set;
    write.dstBinding = w.binding;
    write.descriptorCount = 1;
    write.descriptorType = w.type;
    write.pBufferInfo = w.buffer ? &*w.buffer : nullptr;
    write.pImageInfo = w.image ? &*w.image : nullptr;
    writes.push_back(write);
  }
  vkUpdateDescriptorSets(ctx.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void beginRendering(const Context& ctx, VkCommandBuffer cmd, VkExtent2D extent, std::span<const ColorTarget> colors,
                    const std::optional<DepthTarget>& depth) {
  std::vector<VkRenderingAttachmentInfo> colorInfos;
  colorInfos.reserve(colors.size());
  for (const ColorTarget& color : colors) {
    VkRenderingAttachmentInfo info{};
    info.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    info.imageView = color.view;
    info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    info.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    info.clearValue.color = color.clear;
    colorInfos.push_back(info);
  }
  VkRenderingAttachmentInfo depthInfo{};
  depthInfo.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  if (depth) {
    depthInfo.imageView = depth->view;
    depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depthInfo.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depthInfo.clearValue.depthStencil = {depth->clear, 0};
  }
  VkRenderingInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  info.renderArea = {{0, 0}, extent};
  info.layerCount = 1;
  info.colorAttachmentCount = static_cast<uint32_t>(colorInfos.size());
  info.pColorAttachments = colorInfos.data();
  info.pDepthAttachment = depth ? &depthInfo : nullptr;
  ctx.cmdBeginRendering(cmd, &info);

  const VkViewport viewport{0.0F, 0.0F, static_cast<float>(extent.width), static_cast<float>(extent.height),
                            0.0F, 1.0F};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void endRendering(const Context& ctx, VkCommandBuffer cmd) { ctx.cmdEndRendering(cmd); }

}  // namespace spire::vk

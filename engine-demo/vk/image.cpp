#include "vk/image.h"

#include <algorithm>

#include <fmt/format.h>

namespace spire::vk {
namespace {

struct Access {
  VkPipelineStageFlags stage;
  VkAccessFlags access;
};

// The stages and accesses an image in `layout` is used with, for both sides
// of a barrier. Conservative (e.g. all shader stages for reads) because the
// layout alone does not say which stage the next use is in.
Access layoutAccess(VkImageLayout layout) {
  switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED: return {VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0};
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL:
      return {VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL:
      return {VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT};
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT};
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
      return {VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
              VK_ACCESS_SHADER_READ_BIT};
    default:  // GENERAL and anything else: full barrier.
      return {VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT};
  }
}

}  // namespace

uint32_t formatTexelSize(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM: return 1;
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_R16_SFLOAT: return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT: return 4;
    case VK_FORMAT_R16G16B16A16_UNORM:
    case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: return 0;
  }
}

bool isDepthFormat(VkFormat format) { return format == VK_FORMAT_D32_SFLOAT; }

Expected<Image> Image::create(const Context& ctx, const ImageDesc& desc) {
  if (formatTexelSize(desc.format) == 0) {
    return VkError{VK_ERROR_FORMAT_NOT_SUPPORTED, "Image::create",
                   fmt::format("format {} is not one the engine uses", static_cast<int>(desc.format))};
  }
  if (desc.width == 0 || desc.height == 0) {
    return VkError{VK_ERROR_INITIALIZATION_FAILED, "Image::create", "zero extent"};
  }
  // Ask the device first so an unsupported format/usage pair is an error value
  // rather than a validation error.
  VkImageFormatProperties formatProps;
  if (auto result = vkGetPhysicalDeviceImageFormatProperties(ctx.physicalDevice(), desc.format, VK_IMAGE_TYPE_2D,
                                                             VK_IMAGE_TILING_OPTIMAL, desc.usage, 0, &formatProps);
      result != VK_SUCCESS) {
    return VkError{result, "vkGetPhysicalDeviceImageFormatProperties", {}};
  }
  if (desc.arrayLayers > formatProps.maxArrayLayers) {
    return VkError{VK_ERROR_FORMAT_NOT_SUPPORTED, "Image::create",
                   fmt::format("{} array layers, the device allows {}", desc.arrayLayers, formatProps.maxArrayLayers)};
  }

  Image image;
  image.format_ = desc.format;
  image.extent_ = {desc.width, desc.height};
  image.layers_ = std::max(desc.arrayLayers, 1U);

  VkImageCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = 1;
  info.arrayLayers = image.layers_;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage raw = VK_NULL_HANDLE;
  if (auto result = vkCreateImage(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreateImage", {}};
  }
  image.image_ = makeDeviceHandle<VkImage, vkDestroyImage>(ctx.device(), raw);

  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(ctx.device(), raw, &requirements);
  auto memory = ctx.allocateMemory(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (!memory) return memory.error();
  image.memory_ = std::move(*memory);
  if (auto ok = check(vkBindImageMemory(ctx.device(), raw, image.memory_.get(), 0), "vkBindImageMemory"); !ok)
    return ok.error();

  VkImageViewCreateInfo viewInfo{};

  viewInfo.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  viewInfo.image = raw;
  viewInfo.viewType = desc.arrayLayers > 0 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = desc.format;
  viewInfo.subresourceRange = {image.aspect(), 0, 1, 0, image.layers_};
  VkImageView view = VK_NULL_HANDLE;
  if (auto result = vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view); result != VK_SUCCESS) {
    return VkError{result, "vkCreateImageView", {}};
  }
  image.view_ = makeDeviceHandle<VkImageView, vkDestroyImageView>(ctx.device(), view);
  return image;
}

void Image::transition(VkCommandBuffer cmd, VkImageLayout newLayout) {
  const Access src = layoutAccess(layout_);
  const Access dst = layoutAccess(newLayout);
  VkImageMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  barrier.srcAccessMask = src.access;
  barrier.dstAccessMask = dst.access;
  barrier.oldLayout = layout_;
  barrier.newLayout = newLayout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image_.get();
  barrier.subresourceRange = {aspect(), 0, 1, 0, layers_};
  vkCmdPipelineBarrier(cmd, src.stage, dst.stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
  layout_ = newLayout;
}

Expected<void> Image::copyToBuffer(VkCommandBuffer cmd, const Buffer& dst) {
  if (dst.size() < byteSize()) {
    return VkError{VK_ERROR_OUT_OF_DEVICE_MEMORY, "Image::copyToBuffer",
                   fmt::format("buffer holds {} bytes, image needs {}", dst.size(), byteSize())};
  }
  transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  VkBufferImageCopy region{};
  region.imageSubresource = {aspect(), 0, 0, 1};
  region.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyImageToBuffer(cmd, image_.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.handle(), 1, &region);
  // Make the transfer write visible to host reads of the mapped buffer after
  // the submission's fence.
  VkMemoryBarrier toHost{};
  toHost.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                       nullptr);
  return {};
}

Expected<void> Image::copyFromBuffer(VkCommandBuffer cmd, const Buffer& src) {
  if (src.size() < byteSize()) {
    return VkError{VK_ERROR_OUT_OF_DEVICE_MEMORY, "Image::copyFromBuffer",
                   fmt::format("buffer holds {} bytes, image needs {}", src.size(), byteSize())};
  }
  transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkBufferImageCopy region{};
  region.imageSubresource = {aspect(), 0, 0, 1};
  region.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyBufferToImage(cmd, src.handle(), image_.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  return {};
}

Expected<void> Image::copyLayerFrom(VkCommandBuffer cmd, Image& src, uint32_t layer) {
  if (layer >= layers_ || src.format_ != format_ || src.extent_.width != extent_.width ||
      src.extent_.height != extent_.height || src.layers_ != 1) {
    return VkError{VK_ERROR_FORMAT_NOT_SUPPORTED, "Image::copyLayerFrom",
                   fmt::format("a {}x{} image of format {} does not fit layer {} of a {}x{}x{} array of format {}",
                               src.extent_.width, src.extent_.height, static_cast<int>(src.format_), layer,
                               extent_.width, extent_.height, layers_, static_cast<int>(format_))};
  }
  src.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkImageCopy region{};
  region.srcSubresource = {aspect(), 0, 0, 1};
  region.dstSubresource = {aspect(), 0, layer, 1};
  region.extent = {extent_.width, extent_.height, 1};
  vkCmdCopyImage(cmd, src.image_.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image_.get(),
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  return {};
}

Expected<Sampler> createSampler(const Context& ctx, const SamplerDesc& desc) {
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = desc.filter;
  info.minFilter = desc.filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = desc.addressMode;
  info.addressModeV = desc.addressMode;
  info.addressModeW = desc.addressMode;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler raw = VK_NULL_HANDLE;
  if (auto result = vkCreateSampler(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreateSampler", {}};
  }
  return makeDeviceHandle<VkSampler, vkDestroySampler>(ctx.device(), raw);
}

}  // namespace spire::vk

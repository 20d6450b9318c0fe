#include "vk/frame_blit.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "vk/swapchain.h"

namespace spire::vk {
namespace {

VkFormatFeatureFlags optimalFeatures(const Context& ctx, VkFormat format) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), format, &props);
  return props.optimalTilingFeatures;
}

// The UNORM format whose bytes are laid out like `target`'s, so a copy from
// it is bit-exact; VK_FORMAT_UNDEFINED when there is none the engine knows.
VkFormat stagingFormat(VkFormat target) {
  switch (target) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB: return VK_FORMAT_R8G8B8A8_UNORM;
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB: return VK_FORMAT_B8G8R8A8_UNORM;
    default: return VK_FORMAT_UNDEFINED;
  }
}

struct Barrier {
  VkImageLayout oldLayout;
  VkImageLayout newLayout;
  VkPipelineStageFlags srcStage;
  VkAccessFlags srcAccess;
  VkPipelineStageFlags dstStage;
  VkAccessFlags dstAccess;
};

// The target is a bare VkImage (a swapchain's), so its layout is not tracked
// by vk::Image and every barrier on it is spelled out.
void targetBarrier(VkCommandBuffer cmd, VkImage image, const Barrier& b) {
  VkImageMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  barrier.srcAccessMask = b.srcAccess;
  barrier.dstAccessMask = b.dstAccess;
  barrier.oldLayout = b.oldLayout;
  barrier.newLayout = b.newLayout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, b.srcStage, b.dstStage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

VkImageBlit blitRegion(VkExtent2D source, VkRect2D target) {
  VkImageBlit region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.srcOffsets[1] = {static_cast<int32_t>(source.width), static_cast<int32_t>(source.height), 1};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstOffsets[0] = {target.offset.x, target.offset.y, 0};
  region.dstOffsets[1] = {target.offset.x + static_cast<int32_t>(target.extent.width),
                          target.offset.y + static_cast<int32_t>(target.extent.height), 1};
  return region;
}

// The centre of the frame at the centre of the target: the overlap of both
// when neither contains the other.
VkImageCopy centredCopy(VkExtent2D source, VkExtent2D target) {
  const uint32_t width = std::min(source.width, target.width);
  const uint32_t height = std::min(source.height, target.height);
  VkImageCopy region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.srcOffset = {static_cast<int32_t>((source.width - width) / 2),
                      static_cast<int32_t>((source.height - height) / 2), 0};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstOffset = {static_cast<int32_t>((target.width - width) / 2),
                      static_cast<int32_t>((target.height - height) / 2), 0};
  region.extent = {width, height, 1};
  return region;
}

}  // namespace

BlitPath chooseBlitPath(const Context& ctx, VkFormat target) {
  return (optimalFeatures(ctx, target) & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0 ? BlitPath::Direct : BlitPath::Staged;
}

VkRect2D fitRect(VkExtent2D source, VkExtent2D target) {
  const double scale = std::min(static_cast<double>(target.width) / std::max(source.width, 1U),
                                static_cast<double>(target.height) / std::max(source.height, 1U));
  const auto fit = [&](uint32_t size, uint32_t limit) {
    return std::clamp(static_cast<uint32_t>(std::lround(size * scale)), 1U, std::max(limit, 1U));
  };
  VkRect2D rect{};
  rect.extent = {fit(source.width, target.width), fit(source.height, target.height)};
  rect.offset = {static_cast<int32_t>((target.width - std::min(rect.extent.width, target.width)) / 2),
                 static_cast<int32_t>((target.height - std::min(rect.extent.height, target.height)) / 2)};
  return rect;
}

Expected<FrameBlit> FrameBlit::create(const Context& ctx, BlitPath path, VkFormat sourceFormat, VkExtent2D sourceExtent,
                                      VkFormat targetFormat) {
  const VkFormatFeatureFlags sourceFeatures = optimalFeatures(ctx, sourceFormat);
  if ((sourceFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT) == 0) {
    return VkError{VK_ERROR_FORMAT_NOT_SUPPORTED, "FrameBlit::create",
                   fmt::format("format {} cannot be a blit source", static_cast<int>(sourceFormat))};
  }
  FrameBlit blit;
  blit.path_ = path;
  blit.sourceFormat_ = sourceFormat;
  blit.sourceExtent_ = sourceExtent;
  // Linear filtering of float formats is optional; scaling without it is
  // blockier but still correct.
  blit.filter_ =
      (sourceFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0 ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  if (path == BlitPath::Staged) {
    const VkFormat staging = stagingFormat(targetFormat);
    if (staging == VK_FORMAT_UNDEFINED) {
      return VkError{VK_ERROR_FORMAT_NOT_SUPPORTED, "FrameBlit::create",
                     fmt::format("format {} supports no blits and has no 8-bit RGBA or BGRA layout to copy from",
                                 static_cast<int>(targetFormat))};
    }
    // SAMPLED is never used: vk::Image always makes a view, and a view needs
    // a usage beyond transfers.
    auto image = Image::create(
        ctx, {sourceExtent.width, sourceExtent.height, staging,
              VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    if (!image) return image.error();
    blit.staging_ = std::move(image).value();
  }
  return blit;
}

Expected<void> FrameBlit::record(VkCommandBuffer cmd, Image& source, VkImage target, VkExtent2D targetExtent,
                                 VkImageLayout finalLayout) {
  if (source.format() != sourceFormat_ || source.extent().width != sourceExtent_.width ||
      source.extent().height != sourceExtent_.height) {
    return VkError{VK_ERROR_INITIALIZATION_FAILED, "FrameBlit::record",
                   fmt::format("the frame is {}x{} in format {}, the blit was made for {}x{} in format {}",
                               source.extent().width, source.extent().height, static_cast<int>(source.format()),
                               sourceExtent_.width, sourceExtent_.height, static_cast<int>(sourceFormat_))};
  }
  source.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  targetBarrier(cmd, target,
                {VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, Swapchain::kImageWaitStage, 0,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT});
  // Black bars around a frame whose aspect ratio differs from the window's.
  VkClearColorValue black{};
  black.float32[3] = 1.0F;
  const VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &whole);
  targetBarrier(
      cmd, target,
      {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
       VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT});
  if (path_ == BlitPath::Direct) {
    const VkImageBlit region = blitRegion(sourceExtent_, fitRect(sourceExtent_, targetExtent));
    vkCmdBlitImage(cmd, source.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, filter_);
  } else {
    staging_->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    const VkImageBlit convert = blitRegion(sourceExtent_, {{0, 0}, sourceExtent_});
    vkCmdBlitImage(cmd, source.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging_->handle(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &convert, VK_FILTER_NEAREST);
    staging_->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    const VkImageCopy region = centredCopy(sourceExtent_, targetExtent);
    vkCmdCopyImage(cmd, staging_->handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  }
  // Whatever comes next (presentation, a readback) waits for the writes.
  targetBarrier(
      cmd, target,
      {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, finalLayout, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT});
  return {};
}

}  // namespace spire::vk

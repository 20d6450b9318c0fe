// 2D device-local images (render targets, textures, depth buffers, texture
// arrays) with a view, tracked layout transitions and copy-to-buffer readback; samplers.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/handle.h"
#include "vk/result.h"

namespace spire::vk {

// Bytes per texel of the formats the engine uses (R8, RG8, RGBA8, BGRA8,
// A2B10G10R10 and RGBA16 unorm; R16, RG16, RGBA16, R32 and RGBA32 float; D32
// float); 0 for others.
uint32_t formatTexelSize(VkFormat format);
bool isDepthFormat(VkFormat format);

struct ImageDesc {
  uint32_t width = 0;
  uint32_t height = 0;
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageUsageFlags usage = 0;
  // More than 0: an array of that many layers whose view is a 2D array
  // (sampler2DArray); 0: one layer with a 2D view.
  uint32_t arrayLayers = 0;
};

class Image {
 public:
  // Fails with VK_ERROR_FORMAT_NOT_SUPPORTED for formats outside the list
  // above or not supported by the device for `usage`.
  static Expected<Image> create(const Context& ctx, const ImageDesc& desc);

  VkImage handle() const { return image_.get(); }
  VkImageView view() const { return view_.get(); }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  uint32_t layerCount() const { return layers_; }
  VkImageAspectFlags aspect() const {
    return isDepthFormat(format_) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  }
  // Bytes needed to read the whole image back with copyToBuffer.
  VkDeviceSize byteSize() const { return VkDeviceSize{extent_.width} * extent_.height * formatTexelSize(format_); }

  // The layout as of the last recorded transition. Tracking happens at record
  // time, so command buffers must be submitted in the order they were
  // recorded (true for Context::submitAndWait).
  VkImageLayout layout() const { return layout_; }

  // Records a barrier from the current to `newLayout`, with stage and access
  // masks derived from both layouts (Undefined discards the contents).
  void transition(VkCommandBuffer cmd, VkImageLayout newLayout);

  // Transitions to TRANSFER_SRC_OPTIMAL, copies the whole image tightly packed
  // into `dst` and makes the copy visible to the host. `dst` must hold
  // byteSize() bytes and have TRANSFER_DST usage.
  Expected<void> copyToBuffer(VkCommandBuffer cmd, const Buffer& dst);
  // Transitions to TRANSFER_DST_OPTIMAL and copies
  // byteSize() tightly packed bytes from `src` into the whole image. `src`
  // must have TRANSFER_SRC usage.
  Expected<void> copyFromBuffer(VkCommandBuffer cmd, const Buffer& src);
  // Transitions both images and copies the whole of `src` (one layer, same
  // extent and format) into layer `layer` of this image; for texture arrays
  // assembled from separately baked textures.
  Expected<void> copyLayerFrom(VkCommandBuffer cmd, Image& src, uint32_t layer);

 private:
  Image() = default;

  DeviceMemory memory_;
  ImageHandle image_;
  ImageView view_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
  uint32_t layers_ = 1;
};

struct SamplerDesc {
  VkFilter filter = VK_FILTER_LINEAR;
  VkSamplerAddressMode addressMode = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
};

Expected<Sampler> createSampler(const Context& ctx, const SamplerDesc& desc = {});

}  // namespace spire::vk

// Putting a rendered frame into an image to present: the engine renders
// RGBA32F, swapchains hold display formats. One vkCmdBlitImage converts and
// scales when the target format supports BLIT_DST; otherwise the frame is
// blitted into an 8-bit staging image with the target's byte order (which
// every device can blit to) and copied over, since copies need no format
// feature but cannot convert or scale.
#pragma once

#include <vulkan/vulkan.h>

#include <optional>

#include "vk/context.h"
#include "vk/image.h"
#include "vk/result.h"

namespace spire::vk {

enum class BlitPath {
  Direct,  // a blit into the target, scaled to fit
  Staged,  // a blit into a staging image of the frame's size, then a copy, centred and unscaled
};

// Direct when `target` supports BLIT_DST with optimal tiling, else Staged.
BlitPath chooseBlitPath(const Context& ctx, VkFormat target);

// The largest rectangle with the aspect ratio of `source` that fits in
// `target`, centred; at least 1x1.
VkRect2D fitRect(VkExtent2D source, VkExtent2D target);

class FrameBlit {
 public:
  // For frames of `sourceFormat` (which must support BLIT_SRC) and
  // `sourceExtent` into images of `targetFormat`. Staged needs a target
  // format with the byte order of R8G8B8A8 or B8G8R8A8, UNORM or SRGB (the
  // staging image is UNORM: the copy moves bytes, so the target shows the
  // frame's values without sRGB encoding, like the demo's PNGs).
  // VK_ERROR_FORMAT_NOT_SUPPORTED otherwise.
  static Expected<FrameBlit> create(const Context& ctx, BlitPath path, VkFormat sourceFormat, VkExtent2D sourceExtent,
                                    VkFormat targetFormat);

  BlitPath path() const { return path_; }

  // Records: `source` to TRANSFER_SRC_OPTIMAL; `target` (of `targetExtent`,
  // with TRANSFER_DST usage, its contents discarded) to TRANSFER_DST_OPTIMAL,
  // cleared to black, given the frame, then moved to `finalLayout`. The first
  // barrier on `target` has Swapchain::kImageWaitStage as its source stage.
  // Fails when `source` is not of the format and extent given to create.
  Expected<void> record(VkCommandBuffer cmd, Image& source, VkImage target, VkExtent2D targetExtent,
                        VkImageLayout finalLayout);

 private:
  FrameBlit() = default;

  BlitPath path_ = BlitPath::Direct;
  VkFormat sourceFormat_ = VK_FORMAT_UNDEFINED;
  VkExtent2D sourceExtent_{};
  VkFilter filter_ = VK_FILTER_NEAREST;
  std::optional<Image> staging_;  // Staged only
};

}  // namespace spire::vk

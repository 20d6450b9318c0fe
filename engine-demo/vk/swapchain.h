// The swapchain of a window's surface (Context::create with a surface
// factory): images to present, the semaphores and fences that order
// acquisition, the frame's commands and presentation, and recreation when the
// window is resized or the surface reports it out of date or suboptimal.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "vk/context.h"
#include "vk/handle.h"
#include "vk/result.h"

namespace spire::vk {

// One frame to record: the acquired image (contents undefined, layout
// UNDEFINED) and a command buffer that is already begun.
struct SwapchainFrame {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkImage image = VK_NULL_HANDLE;
  VkExtent2D extent{};
};

class Swapchain {
 public:
  // Frames recorded while earlier ones are still drawn or presented.
  static constexpr uint32_t kFramesInFlight = 2;
  // The frame's submission waits for its image to be acquired at this stage,
  // so the first barrier on the image must have it in its source stages.
  static constexpr VkPipelineStageFlags kImageWaitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;

  // `windowExtent` is the window's framebuffer size in pixels, used when the
  // surface leaves the size to the swapchain. Images have TRANSFER_DST usage
  // only (frames are blitted or copied in); the format is B8G8R8A8_UNORM or
  // R8G8B8A8_UNORM when the surface offers one (the engine's colors are
  // display values already, which an sRGB format would encode again), else
  // the surface's first.
  static Expected<Swapchain> create(const Context& ctx, VkExtent2D windowExtent);

  Swapchain(Swapchain&&) noexcept = default;
  Swapchain& operator=(Swapchain&&) = delete;

  VkFormat format() const { return format_.format; }
  VkExtent2D extent() const { return extent_; }

  // Waits until the oldest frame in flight finished, recreates the swapchain
  // when the window size changed or the surface reported it out of date or
  // suboptimal, acquires an image and begins the frame's command buffer.
  // std::nullopt when there is nothing to present to now (a minimized window,
  // or the surface went out of date during acquisition): skip the frame.
  Expected<std::optional<SwapchainFrame>> beginFrame(VkExtent2D windowExtent);
  // Ends and submits the frame begun by beginFrame and presents its image,
  // which the recorded commands must leave in PRESENT_SRC_KHR. An out of date
  // or suboptimal surface is not an error: the next beginFrame recreates.
  Expected<void> endFrame();

 private:
  Swapchain() = default;
  // Rebuilds the swapchain for the surface's current size after the device
  // went idle; false (and nothing changed) when that size is zero.
  Expected<bool> rebuild(VkExtent2D windowExtent);

  struct FrameSlot {
    CommandBuffer cmd;
    Semaphore acquired;  // signalled by acquisition, waited on by the submission
    Fence finished;      // signalled by the submission, waited on before the slot is reused
  };

  const Context* ctx_ = nullptr;
  VkSurfaceFormatKHR format_{};
  VkExtent2D extent_{};
  VkExtent2D windowExtent_{};  // what the swapchain was last built for
  bool stale_ = false;         // out of date or suboptimal: rebuild before the next frame
  SwapchainHandle swapchain_;
  std::vector<VkImage> images_;  // owned by the swapchain
  // Per image rather than per slot: a presentation may still wait on its
  // semaphore when the slot comes round again, but not once its image has
  // been acquired again.
  std::vector<Semaphore> rendered_;
  std::vector<FrameSlot> slots_;
  uint32_t slot_ = 0;
  uint32_t imageIndex_ = 0;
  // Declared last, so destroyed first: the members above may still be in use
  // by submitted frames until the device is idle.
  WaitIdleOnDestroy waitIdle_;
};

}  // namespace spire::vk

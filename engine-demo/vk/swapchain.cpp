#include "vk/swapchain.h"

#include <fmt/format.h>

#include <algorithm>

namespace spire::vk {
namespace {

Expected<VkSurfaceFormatKHR> chooseFormat(const Context& ctx) {
  uint32_t count = 0;
  if (auto ok = check(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), ctx.surface(), &count, nullptr),
                      "vkGetPhysicalDeviceSurfaceFormatsKHR");
      !ok) {
    return ok.error();
  }
  std::vector<VkSurfaceFormatKHR> formats(count);
  if (auto ok = check(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), ctx.surface(), &count, formats.data()),
                      "vkGetPhysicalDeviceSurfaceFormatsKHR");
      !ok) {
    return ok.error();
  }
  if (formats.empty()) return VkError{VK_ERROR_FORMAT_NOT_SUPPORTED, "Swapchain::create", "the surface has no formats"};
  for (const VkFormat preferred : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM}) {
    for (const VkSurfaceFormatKHR& format : formats) {
      if (format.format == preferred && format.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return format;
    }
  }
  return formats.front();
}

Expected<Semaphore> createSemaphore(VkDevice device) {
  VkSemaphoreCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  VkSemaphore raw = VK_NULL_HANDLE;
  if (auto ok = check(vkCreateSemaphore(device, &info, nullptr, &raw), "vkCreateSemaphore"); !ok) return ok.error();
  return makeDeviceHandle<VkSemaphore, vkDestroySemaphore>(device, raw);
}

// Created signalled, so the first wait on a fresh slot returns at once.
Expected<Fence> createSignalledFence(VkDevice device) {
  VkFenceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VkFence raw = VK_NULL_HANDLE;
  if (auto ok = check(vkCreateFence(device, &info, nullptr, &raw), "vkCreateFence"); !ok) return ok.error();
  return makeDeviceHandle<VkFence, vkDestroyFence>(device, raw);
}

Expected<CommandBuffer> allocateCommandBuffer(const Context& ctx) {
  VkCommandBufferAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  info.commandPool = ctx.commandPool();
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer raw = VK_NULL_HANDLE;
  if (auto ok = check(vkAllocateCommandBuffers(ctx.device(), &info, &raw), "vkAllocateCommandBuffers"); !ok) {
    return ok.error();
  }
  return CommandBuffer(raw, {ctx.device(), ctx.commandPool()});
}

bool sameExtent(VkExtent2D a, VkExtent2D b) { return a.width == b.width && a.height == b.height; }

}  // namespace

Expected<Swapchain> Swapchain::create(const Context& ctx, VkExtent2D windowExtent) {
  if (ctx.surface() == VK_NULL_HANDLE) {
    return VkError{VK_ERROR_INITIALIZATION_FAILED, "Swapchain::create", "the context was created without a surface"};
  }
  Swapchain swapchain;
  swapchain.ctx_ = &ctx;
  swapchain.waitIdle_ = WaitIdleOnDestroy(ctx.device(), {});
  auto format = chooseFormat(ctx);
  if (!format) return format.error();
  swapchain.format_ = *format;
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    auto cmd = allocateCommandBuffer(ctx);
    if (!cmd) return cmd.error();
    auto acquired = createSemaphore(ctx.device());
    if (!acquired) return acquired.error();
    auto finished = createSignalledFence(ctx.device());
    if (!finished) return finished.error();
    swapchain.slots_.push_back({std::move(cmd).value(), std::move(acquired).value(), std::move(finished).value()});
  }
  // A window minimized at start has no size yet; the first beginFrame that
  // finds one builds the swapchain.
  if (auto built = swapchain.rebuild(windowExtent); !built) return built.error();
  return swapchain;
}

Expected<bool> Swapchain::rebuild(VkExtent2D windowExtent) {
  const VkDevice device = ctx_->device();
  // The old swapchain's images and the per-image semaphores may still be used
  // by frames in flight.
  {
    const auto queueLock = ctx_->lockQueue();
    if (auto ok = check(vkDeviceWaitIdle(device), "vkDeviceWaitIdle"); !ok) return ok.error();
  }
  VkSurfaceCapabilitiesKHR caps;
  if (auto ok = check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_->physicalDevice(), ctx_->surface(), &caps),
                      "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
      !ok) {
    return ok.error();
  }
  VkExtent2D extent = caps.currentExtent;
  // 0xFFFFFFFF: the surface takes its size from the swapchain.
  if (extent.width == UINT32_MAX) {
    extent.width = std::clamp(windowExtent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(windowExtent.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0) return false;
  if ((caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) == 0) {
    return VkError{VK_ERROR_FEATURE_NOT_PRESENT, "Swapchain::create",
                   "the surface's images cannot be transfer destinations"};
  }
  // One more than the minimum, so acquisition need not wait for the
  // presentation engine to release an image.
  uint32_t imageCount = caps.minImageCount + 1;
  if (caps.maxImageCount != 0) imageCount = std::min(imageCount, caps.maxImageCount);
  VkCompositeAlphaFlagBitsKHR alpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  if ((caps.supportedCompositeAlpha & alpha) == 0) {
    // The lowest supported mode; every surface supports at least one.
    const VkCompositeAlphaFlagsKHR supported = caps.supportedCompositeAlpha;
    alpha = static_cast<VkCompositeAlphaFlagBitsKHR>(supported & (~supported + 1));
  }

  VkSwapchainCreateInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
  info.surface = ctx_->surface();
  info.minImageCount = imageCount;
  info.imageFormat = format_.format;
  info.imageColorSpace = format_.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = alpha;
  // FIFO is the one mode every surface supports.
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
  info.clipped = VK_TRUE;
  info.oldSwapchain = swapchain_.get();
  VkSwapchainKHR raw = VK_NULL_HANDLE;
  if (auto ok = check(vkCreateSwapchainKHR(device, &info, nullptr, &raw), "vkCreateSwapchainKHR"); !ok) {
    return ok.error();
  }
  // Destroys the old swapchain, now retired by the new one.
  swapchain_ = makeDeviceHandle<VkSwapchainKHR, vkDestroySwapchainKHR>(device, raw);

  uint32_t count = 0;
  if (auto ok = check(vkGetSwapchainImagesKHR(device, raw, &count, nullptr), "vkGetSwapchainImagesKHR"); !ok) {
    return ok.error();
  }
  images_.assign(count, VK_NULL_HANDLE);
  if (auto ok = check(vkGetSwapchainImagesKHR(device, raw, &count, images_.data()), "vkGetSwapchainImagesKHR"); !ok) {
    return ok.error();
  }
  rendered_.clear();
  for (uint32_t i = 0; i < count; ++i) {
    auto semaphore = createSemaphore(device);
    if (!semaphore) return semaphore.error();
    rendered_.push_back(std::move(semaphore).value());
  }
  extent_ = extent;
  windowExtent_ = windowExtent;
  stale_ = false;
  return true;
}

Expected<std::optional<SwapchainFrame>> Swapchain::beginFrame(VkExtent2D windowExtent) {
  if (windowExtent.width == 0 || windowExtent.height == 0) return std::optional<SwapchainFrame>();
  if (!swapchain_ || stale_ || !sameExtent(windowExtent, windowExtent_)) {
    auto built = rebuild(windowExtent);
    if (!built) return built.error();
    if (!*built) return std::optional<SwapchainFrame>();
  }
  const VkDevice device = ctx_->device();
  FrameSlot& slot = slots_[slot_];
  const VkFence fence = slot.finished.get();
  if (auto ok = check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences"); !ok) {
    return ok.error();
  }
  const VkResult acquired =
      vkAcquireNextImageKHR(device, swapchain_.get(), UINT64_MAX, slot.acquired.get(), VK_NULL_HANDLE, &imageIndex_);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    // Nothing was acquired and the semaphore stays unsignalled.
    stale_ = true;
    return std::optional<SwapchainFrame>();
  }
  if (acquired == VK_SUBOPTIMAL_KHR) {
    // The image was acquired and can still be presented: draw this frame.
    stale_ = true;
  } else if (acquired != VK_SUCCESS) {
    return VkError{acquired, "vkAcquireNextImageKHR", {}};
  }
  const VkCommandBuffer cmd = slot.cmd.get();
  if (auto ok = check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer"); !ok) return ok.error();
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (auto ok = check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer"); !ok) return ok.error();
  return std::optional<SwapchainFrame>(SwapchainFrame{cmd, images_[imageIndex_], extent_});
}

Expected<void> Swapchain::endFrame() {
  FrameSlot& slot = slots_[slot_];
  slot_ = (slot_ + 1) % kFramesInFlight;
  const VkCommandBuffer cmd = slot.cmd.get();
  if (auto ok = check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer"); !ok) return ok;
  // Reset only now, right before the submission that signals it again: a
  // frame abandoned between beginFrame and here must not leave the slot's
  // fence unsignalled forever.
  const VkFence fence = slot.finished.get();
  if (auto ok = check(vkResetFences(ctx_->device(), 1, &fence), "vkResetFences"); !ok) return ok;

  const VkSemaphore acquired = slot.acquired.get();
  const VkSemaphore rendered = rendered_[imageIndex_].get();
  const VkPipelineStageFlags waitStage = kImageWaitStage;
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &acquired;
  submit.pWaitDstStageMask = &waitStage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &rendered;
  // Another thread may be submitting bakes (Context::submitAndWait).
  const auto queueLock = ctx_->lockQueue();
  if (auto ok = check(vkQueueSubmit(ctx_->queue(), 1, &submit, fence), "vkQueueSubmit"); !ok) return ok;

  const VkSwapchainKHR swapchain = swapchain_.get();
  VkPresentInfoKHR present{};
  present.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &rendered;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain;
  present.pImageIndices = &imageIndex_;
  const VkResult presented = vkQueuePresentKHR(ctx_->queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
    stale_ = true;
    return {};
  }
  return check(presented, "vkQueuePresentKHR");
}

}  // namespace spire::vk

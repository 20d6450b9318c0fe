// How spire-explore shows a frame in its window, in every mode: the shown
// image with the Dear ImGui panels drawn over it, blitted to the swapchain
// (kept transfer-only, as spire-demo --window has it); and the images the
// scripts' screenshots write.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "demo/glfw_window.h"
#include "explore/imgui_overlay.h"
#include "measure/image_metrics.h"
#include "renderer/error.h"
#include "vk/frame_blit.h"
#include "vk/image.h"
#include "vk/swapchain.h"

namespace spire::explore {

class WindowPresenter {
 public:
  // For images like `shown` (the renderer's color target) presented to
  // `window`, whose surface `ctx` was made with.
  static engine::Expected<std::unique_ptr<WindowPresenter>> create(const vk::Context& ctx, demo::GlfwWindow& window,
                                                                   const vk::Image& shown);

  // Draws the panels over `shown` and presents it: `prepare` first records
  // what puts the image in `shown` (a copy), then `panels` draws into the
  // ImGui frame. Nothing is drawn while the window is minimized.
  engine::Expected<void> present(vk::Image& shown, const std::function<void()>& panels,
                                 const std::function<vk::Expected<void>(VkCommandBuffer)>& prepare = {});
  bool wantsMouse() const { return overlay_->wantsMouse(); }

 private:
  WindowPresenter(demo::GlfwWindow& window, vk::Swapchain swapchain, vk::FrameBlit blit,
                  std::unique_ptr<ImGuiOverlay> overlay)
      : window_(window), swapchain_(std::move(swapchain)), blit_(std::move(blit)), overlay_(std::move(overlay)) {}

  demo::GlfwWindow& window_;
  vk::Swapchain swapchain_;
  vk::FrameBlit blit_;
  std::unique_ptr<ImGuiOverlay> overlay_;
};

// The explorer's frame loop: polls `window` and runs `frame` until it
// returns false (the script ended), the user closes the window, or
// `maxFrames` frames were shown (--frames). Stops at the first error.
engine::Expected<void> runFrameLoop(demo::GlfwWindow& window, std::optional<uint64_t> maxFrames,
                                    const std::function<engine::Expected<bool>(const demo::WindowInput&)>& frame);

// `image` as an opaque PNG, as spire-demo writes its images.
engine::Expected<void> writeOpaquePng(const std::filesystem::path& path, const measure::FloatImage& image);
// An RGBA32F image of the device read back and written so.
engine::Expected<void> writeImagePng(const vk::Context& ctx, vk::Image& image, const std::filesystem::path& path);

}  // namespace spire::explore

// Dear ImGui on the engine's Vulkan context (Debian's libimgui-dev 1.86, whose
// GLFW and Vulkan backends are in libimgui.a): the explorer's panels are
// drawn over the image about to be shown, before it is blitted to the
// window, so the swapchain stays transfer-only as spire-demo --window has it.
// The 1.86 Vulkan backend needs a VkRenderPass: one over a single color
// attachment of the shown image's format, loaded and stored in
// COLOR_ATTACHMENT_OPTIMAL. One overlay per process (ImGui's context is
// global).
#pragma once

#include <vulkan/vulkan.h>

#include <deque>
#include <memory>

#include "vk/context.h"
#include "vk/handle.h"
#include "vk/image.h"

struct GLFWwindow;

namespace spire::explore {

class ImGuiOverlay {
 public:
  // Sets up ImGui for `window` (installing its callbacks, which chain to the
  // window's own) and for images of `format`, and uploads the font.
  static vk::Expected<std::unique_ptr<ImGuiOverlay>> create(const vk::Context& ctx, GLFWwindow* window,
                                                            VkFormat format);
  ImGuiOverlay(const ImGuiOverlay&) = delete;
  ImGuiOverlay& operator=(const ImGuiOverlay&) = delete;
  ~ImGuiOverlay();

  // Starts a UI frame for an image of `extent` shown stretched over the
  // window: ImGui lays out in image pixels, and the cursor is mapped there.
  void beginFrame(VkExtent2D extent);
  // Ends the frame and records its drawing into `target` (transitioned to
  // COLOR_ATTACHMENT_OPTIMAL, left there).
  vk::Expected<void> record(VkCommandBuffer cmd, vk::Image& target);

  // Whether ImGui uses the mouse or keyboard now (so the camera must not).
  bool wantsMouse() const;
  bool wantsKeyboard() const;

 private:
  explicit ImGuiOverlay(const vk::Context& ctx) : ctx_(&ctx) {}
  vk::Expected<VkFramebuffer> framebufferFor(const vk::Image& target);

  const vk::Context* ctx_;
  GLFWwindow* window_ = nullptr;
  vk::DescriptorPool pool_;
  vk::RenderPass renderPass_;
  // One per recorded frame, kept while frames in flight may still use it:
  // the shown image can change between frames (another view mode, a render
  // target made again), and a handle's value can be reused after it is gone.
  std::deque<vk::Framebuffer> framebuffers_;
  bool glfwReady_ = false;
  bool vulkanReady_ = false;
};

}  // namespace spire::explore

// The window of spire-demo --window, through GLFW: whether one can be opened
// at all, the Vulkan surface on it, and the user's keys and mouse drags.
#pragma once

#include <vulkan/vulkan.h>

#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "support/expected.h"
#include "vk/result.h"

struct GLFWwindow;

namespace spire::demo {

// What the user did since the last poll.
struct WindowInput {
  bool quit = false;              // Escape, or the window's close button
  std::optional<size_t> variant;  // the last number key pressed: 1..9 as index 0..8
  bool togglePause = false;       // Space pressed an odd number of times
  glm::vec2 drag{0.0F};           // cursor movement in pixels while the left button was held
};

class GlfwWindow {
 public:
  // Initializes GLFW and opens a `width` x `height` window without a client
  // API (Vulkan presents to it). The error is a sentence for the user:
  // "--window needs a display (...)" when there is none (neither DISPLAY nor
  // WAYLAND_DISPLAY is set, or GLFW cannot connect to it), otherwise why
  // GLFW could not open a Vulkan window.
  static spire::Expected<GlfwWindow, std::string> open(uint32_t width, uint32_t height, const std::string& title);

  GlfwWindow(GlfwWindow&& other) noexcept;
  GlfwWindow& operator=(GlfwWindow&&) = delete;
  ~GlfwWindow();

  // The instance extensions a surface on the window needs (VK_KHR_surface
  // and the platform's), for vk::ContextOptions::instanceExtensions.
  std::vector<std::string> vulkanInstanceExtensions() const;
  // A surface on the window, for vk::Context::create's surface factory; the
  // window must outlive it.
  vk::Expected<VkSurfaceKHR> createSurface(VkInstance instance) const;

  // Handles pending window events, first waiting up to `waitSeconds` for one
  // (for when there is nothing to draw), and returns the input since the
  // last poll.
  WindowInput poll(double waitSeconds = 0.0);
  // The drawable size in pixels; zero while minimized.
  VkExtent2D framebufferExtent() const;
  void setTitle(const std::string& title);
  // For libraries that drive the window themselves (the explorer's Dear ImGui
  // backend installs its callbacks over this class's and chains to them).
  GLFWwindow* glfwHandle() const;

 private:
  struct State;
  explicit GlfwWindow(std::unique_ptr<State> state);

  // On the heap, so the pointer GLFW's callbacks get stays valid when the
  // window moves.
  std::unique_ptr<State> state_;
};

}  // namespace spire::demo

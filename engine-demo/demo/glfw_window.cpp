#include "demo/glfw_window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace spire::demo {

namespace {

// GLFW's description of its last error.
std::string glfwErrorText() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description != nullptr ? description : "no description";
}

bool environmentSet(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && value[0] != '\0';
}

}  // namespace

// Exists only while GLFW is initialized: its destructor closes the window and
// terminates GLFW. GLFW's callbacks find it through the window's user pointer.
struct GlfwWindow::State {
  GLFWwindow* window = nullptr;
  WindowInput pending;
  bool dragging = false;
  glm::dvec2 cursor{0.0};

  State() = default;
  State(const State&) = delete;
  State& operator=(const State&) = delete;
  ~State() {
    if (window != nullptr) glfwDestroyWindow(window);
    glfwTerminate();
  }

  static State& of(GLFWwindow* window) { return *static_cast<State*>(glfwGetWindowUserPointer(window)); }

  static void onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
    if (action != GLFW_PRESS) return;
    WindowInput& input = of(window).pending;
    if (key == GLFW_KEY_ESCAPE) input.quit = true;
    if (key == GLFW_KEY_SPACE) input.togglePause = !input.togglePause;
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) input.variant = static_cast<size_t>(key - GLFW_KEY_1);
    if (key >= GLFW_KEY_KP_1 && key <= GLFW_KEY_KP_9) input.variant = static_cast<size_t>(key - GLFW_KEY_KP_1);
  }

  static void onMouseButton(GLFWwindow* window, int button, int action, int /*mods*/) {
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    State& state = of(window);
    state.dragging = action == GLFW_PRESS;
    glfwGetCursorPos(window, &state.cursor.x, &state.cursor.y);
  }

  static void onCursor(GLFWwindow* window, double x, double y) {
    State& state = of(window);
    const glm::dvec2 position{x, y};
    if (state.dragging) state.pending.drag += glm::vec2(position - state.cursor);
    state.cursor = position;
  }
};

GlfwWindow::GlfwWindow(std::unique_ptr<State> state) : state_(std::move(state)) {}
GlfwWindow::GlfwWindow(GlfwWindow&& other) noexcept = default;
GlfwWindow::~GlfwWindow() = default;

spire::Expected<GlfwWindow, std::string> GlfwWindow::open(uint32_t width, uint32_t height, const std::string& title) {
  // Checked first because GLFW's own message for it names only the platform
  // it was built for ("X11: The DISPLAY environment variable is missing").
  if (!environmentSet("DISPLAY") && !environmentSet("WAYLAND_DISPLAY")) {
    return std::string("--window needs a display (neither DISPLAY nor WAYLAND_DISPLAY is set)");
  }
  if (glfwInit() != GLFW_TRUE) return fmt::format("--window needs a display (GLFW: {})", glfwErrorText());
  auto state = std::make_unique<State>();
  if (glfwVulkanSupported() != GLFW_TRUE) {
    return fmt::format("--window cannot present with Vulkan here (GLFW: {})", glfwErrorText());
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  state->window = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), title.c_str(), nullptr, nullptr);
  if (state->window == nullptr) return fmt::format("cannot open a window (GLFW: {})", glfwErrorText());
  glfwSetWindowUserPointer(state->window, state.get());
  glfwSetKeyCallback(state->window, &State::onKey);
  glfwSetMouseButtonCallback(state->window, &State::onMouseButton);
  glfwSetCursorPosCallback(state->window, &State::onCursor);
  return GlfwWindow(std::move(state));
}

std::vector<std::string> GlfwWindow::vulkanInstanceExtensions() const {
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  return names != nullptr ? std::vector<std::string>(names, names + count) : std::vector<std::string>();
}

vk::Expected<VkSurfaceKHR> GlfwWindow::createSurface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  if (const VkResult result = glfwCreateWindowSurface(instance, state_->window, nullptr, &surface);
      result != VK_SUCCESS) {
    return vk::VkError{result, "glfwCreateWindowSurface", glfwErrorText()};
  }
  return surface;
}

WindowInput GlfwWindow::poll(double waitSeconds) {
  if (waitSeconds > 0.0) {
    glfwWaitEventsTimeout(waitSeconds);
  } else {
    glfwPollEvents();
  }
  WindowInput input = std::exchange(state_->pending, WindowInput{});
  input.quit = input.quit || glfwWindowShouldClose(state_->window) == GLFW_TRUE;
  return input;
}

VkExtent2D GlfwWindow::framebufferExtent() const {
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(state_->window, &width, &height);
  return {static_cast<uint32_t>(std::max(width, 0)), static_cast<uint32_t>(std::max(height, 0))};
}

GLFWwindow* GlfwWindow::glfwHandle() const { return state_->window; }

void GlfwWindow::setTitle(const std::string& title) { glfwSetWindowTitle(state_->window, title.c_str()); }

}  // namespace spire::demo

#include "explore/window_presenter.h"

#include <cstring>

#include "renderer/gpu_resources.h"
#include "scene/texture.h"

namespace spire::explore {

engine::Expected<std::unique_ptr<WindowPresenter>> WindowPresenter::create(const vk::Context& ctx,
                                                                           demo::GlfwWindow& window,
                                                                           const vk::Image& shown) {
  auto swapchain = vk::Swapchain::create(ctx, window.framebufferExtent());
  if (!swapchain) return engine::Error::fromVk(swapchain.error());
  auto blit = vk::FrameBlit::create(ctx, vk::chooseBlitPath(ctx, swapchain->format()), shown.format(), shown.extent(),
                                    swapchain->format());
  if (!blit) return engine::Error::fromVk(blit.error());
  auto overlay = ImGuiOverlay::create(ctx, window.glfwHandle(), shown.format());
  if (!overlay) return engine::Error::fromVk(overlay.error());
  return std::unique_ptr<WindowPresenter>(
      new WindowPresenter(window, std::move(swapchain).value(), std::move(blit).value(), std::move(overlay).value()));
}

engine::Expected<void> WindowPresenter::present(vk::Image& shown, const std::function<void()>& panels,
                                                const std::function<vk::Expected<void>(VkCommandBuffer)>& prepare) {
  auto frame = swapchain_.beginFrame(window_.framebufferExtent());
  if (!frame) return engine::Error::fromVk(frame.error());
  if (!frame->has_value()) return {};  // minimized: nothing to present to
  const vk::SwapchainFrame& target = **frame;
  if (prepare) {
    if (auto ok = prepare(target.cmd); !ok) return engine::Error::fromVk(ok.error());
  }
  overlay_->beginFrame(shown.extent());
  panels();
  if (auto ok = overlay_->record(target.cmd, shown); !ok) return engine::Error::fromVk(ok.error());
  if (auto ok = blit_.record(target.cmd, shown, target.image, target.extent, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR); !ok) {
    return engine::Error::fromVk(ok.error());
  }
  if (auto ok = swapchain_.endFrame(); !ok) return engine::Error::fromVk(ok.error());
  return {};
}

engine::Expected<void> runFrameLoop(demo::GlfwWindow& window, std::optional<uint64_t> maxFrames,
                                    const std::function<engine::Expected<bool>(const demo::WindowInput&)>& frame) {
  uint64_t shown = 0;
  while (!maxFrames || shown < *maxFrames) {
    const demo::WindowInput input = window.poll();
    if (input.quit) break;
    auto more = frame(input);
    if (!more) return more.error();
    if (!*more) break;
    ++shown;
  }
  return {};
}

engine::Expected<void> writeOpaquePng(const std::filesystem::path& path, const measure::FloatImage& image) {
  auto ok = scene::writePng(path, measure::opaque(measure::toRgba8(image)));
  if (!ok) return engine::Error{ok.error()};
  return {};
}

engine::Expected<void> writeImagePng(const vk::Context& ctx, vk::Image& image, const std::filesystem::path& path) {
  auto bytes = engine::readImage(ctx, image);
  if (!bytes) return bytes.error();
  measure::FloatImage pixels{image.extent().width, image.extent().height,
                             std::vector<float>(bytes->size() / sizeof(float))};
  std::memcpy(pixels.rgba.data(), bytes->data(), bytes->size());
  return writeOpaquePng(path, pixels);
}

}  // namespace spire::explore

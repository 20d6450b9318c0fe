#include "demo/window.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>

#include "demo/camera_path.h"
#include "vk/frame_blit.h"
#include "vk/swapchain.h"
#include "vk/timer.h"

namespace spire::demo {

namespace {

constexpr double kSecondsPerView = 4.0;     // from one camera view to the next, its rest included
constexpr float kRadiansPerPixel = 0.005F;  // orbit speed of a mouse drag
constexpr double kTitleSeconds = 0.5;       // how often the title's averages are refreshed
constexpr double kIdleWaitSeconds = 0.1;    // event wait while there is nothing to draw to (minimized)

// Frame times averaged over the frames since the title last changed.
class TitleStats {
 public:
  void add(double gpuMs) {
    gpuMs_ += gpuMs;
    ++frames_;
  }
  bool due(double now) const { return now - since_ >= kTitleSeconds; }
  // Forgets the frames so far (another variant is shown from now on).
  void restart(double now) {
    gpuMs_ = 0.0;
    frames_ = 0;
    since_ = now;
  }
  std::string title(const std::string& scene, const std::string& variant, size_t index, size_t count, bool paused,
                    double now) {
    std::string times = "measuring...";
    if (frames_ > 0) {
      times = fmt::format("{:.2f} ms GPU, {:.1f} ms/frame", gpuMs_ / static_cast<double>(frames_),
                          (now - since_) * 1000.0 / static_cast<double>(frames_));
    }
    restart(now);
    return fmt::format("spire-demo | {} | [{}/{}] {} | {}{}", scene, index + 1, count, variant, times,
                       paused ? " | paused" : "");
  }

 private:
  double gpuMs_ = 0.0;
  uint64_t frames_ = 0;
  double since_ = 0.0;
};

std::string keyHelp(std::span<const std::string> names) {
  const size_t keys = std::min<size_t>(names.size(), 9);
  std::string variants = fmt::format("showing {}", names.front());
  if (keys > 1) {
    variants = fmt::format("keys 1-{} switch variants (", keys);
    for (size_t i = 0; i < keys; ++i) variants += fmt::format("{}{} {}", i == 0 ? "" : ", ", i + 1, names[i]);
    variants += ")";
  }
  return fmt::format("window: {}; drag to orbit, Space pauses the camera, Escape quits\n", variants);
}

}  // namespace

FrameSource variantFrames(engine::SceneRenderer& renderer, std::span<const engine::PreparedScene> variants,
                          std::span<const std::string> names) {
  return {std::vector<std::string>(names.begin(), names.end()),
          [&renderer, variants](size_t v, const scene::CameraView& view, float time) {
            return renderer.renderView(variants[v], view, time);
          }};
}

int runWindow(GlfwWindow& window, engine::SceneRenderer& renderer, const FrameSource& source,
              const WindowOptions& options, std::ostream& out, engine::ErrorReporter& reporter) {
  const std::vector<std::string>& names = source.names;
  const vk::Context& ctx = renderer.context();
  const scene::SceneFile& scene = renderer.scene();
  vk::Image* frameImage = renderer.colorImage();
  if (frameImage == nullptr) return reporter.fail({"the scene renders no color output to show", {}, {}});
  auto swapchain = vk::Swapchain::create(ctx, window.framebufferExtent());
  if (!swapchain) return reporter.fail(engine::Error::fromVk(swapchain.error()));
  auto blit = vk::FrameBlit::create(ctx, vk::chooseBlitPath(ctx, swapchain->format()), frameImage->format(),
                                    frameImage->extent(), swapchain->format());
  if (!blit) return reporter.fail(engine::Error::fromVk(blit.error()));
  // One frame of each variant first, so that switching to one is not slowed
  // by lavapipe compiling its shaders at their first draw.
  for (size_t v = 0; v < names.size(); ++v) {
    if (auto warm = source.render(v, scene.camera.views.front(), 0.0F); !warm) return reporter.fail(warm.error());
  }
  out << keyHelp(names) << std::flush;

  size_t current = 0;
  bool paused = false;
  bool idle = false;
  float yaw = 0.0F;
  float pitch = 0.0F;
  double pathSeconds = 0.0;
  double lastSeconds = 0.0;
  uint64_t shown = 0;
  const vk::HostTimer clock;
  TitleStats stats;
  window.setTitle(stats.title(options.sceneName, names[current], current, names.size(), paused, 0.0));
  while (!options.maxFrames || shown < *options.maxFrames) {
    const WindowInput input = window.poll(idle ? kIdleWaitSeconds : 0.0);
    if (input.quit) break;
    const double now = clock.elapsedMs() / 1000.0;
    bool retitle = input.togglePause;
    if (input.variant && *input.variant < names.size() && *input.variant != current) {
      current = *input.variant;
      stats.restart(now);
      retitle = true;
    }
    paused = paused != input.togglePause;
    if (!paused) pathSeconds += now - lastSeconds;
    lastSeconds = now;
    yaw -= input.drag.x * kRadiansPerPixel;
    // Bounded, so dragging past the top or bottom does not have to be undone.
    pitch = std::clamp(pitch + input.drag.y * kRadiansPerPixel, -glm::pi<float>(), glm::pi<float>());

    auto frame = swapchain->beginFrame(window.framebufferExtent());
    if (!frame) return reporter.fail(engine::Error::fromVk(frame.error()));
    idle = !frame->has_value();
    if (idle) continue;
    const scene::CameraView view =
        orbit(cameraOnLoop(scene.camera.views, pathSeconds / kSecondsPerView), scene.camera.up, yaw, pitch);
    auto timing = source.render(current, view, static_cast<float>(now));
    if (!timing) return reporter.fail(timing.error());
    const vk::SwapchainFrame& target = **frame;
    if (auto ok = blit->record(target.cmd, *frameImage, target.image, target.extent, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
        !ok) {
      return reporter.fail(engine::Error::fromVk(ok.error()));
    }
    if (auto ok = swapchain->endFrame(); !ok) return reporter.fail(engine::Error::fromVk(ok.error()));
    ++shown;
    stats.add(timing->gpuMs);
    if (retitle || stats.due(now)) {
      window.setTitle(stats.title(options.sceneName, names[current], current, names.size(), paused, now));
    }
  }
  out << fmt::format("window: {} frames shown\n", shown);
  return 0;
}

}  // namespace spire::demo

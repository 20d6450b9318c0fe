// spire-demo --window: the scene's prepared variants shown interactively,
// with the camera moving through the scene's views, so the trade between
// speed and quality can be seen rather than only measured.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "demo/glfw_window.h"
#include "renderer/scene_renderer.h"
#include "tool/error_report.h"

namespace spire::demo {

struct WindowOptions {
  std::string sceneName;              // shown in the title
  std::optional<uint32_t> maxFrames;  // close after this many frames (--frames); nullopt: when the user does
};

// What the window shows: variants by name, in the order of the number keys,
// each rendered into the renderer's RGBA32F target by `render` (the
// prepared variants of a scene, or the configurations of a
// level-of-detail scene).
struct FrameSource {
  std::vector<std::string> names;
  std::function<engine::Expected<engine::FrameTiming>(size_t variant, const scene::CameraView& view, float time)>
      render;
};

// The prepared variants of `renderer`'s scene, named by `names`.
FrameSource variantFrames(engine::SceneRenderer& renderer, std::span<const engine::PreparedScene> variants,
                          std::span<const std::string> names);

// Shows `source` (rendered through `renderer`, whose context presents to
// `window`) until the user closes the window or presses Escape. Each frame
// renders the current variant and blits the target into the window.
// 1..9 switch variants, dragging with the left button orbits the camera,
// Space stops and resumes its loop; the title shows the frame times. Returns
// the exit status: 0, or 1 after printing a Vulkan or rendering error through
// `reporter`.
int runWindow(GlfwWindow& window, engine::SceneRenderer& renderer, const FrameSource& source,
              const WindowOptions& options, std::ostream& out, engine::ErrorReporter& reporter);

}  // namespace spire::demo

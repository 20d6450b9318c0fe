// spire-demo on a scene with "lod" (docs/lod.md): the scene drawn at full
// quality (every instance at the policy's nearest level), with level of
// detail, and with level of detail but without cross-fades, over the same
// frames of a fly-through of the scene's camera views. Frames of the three
// are rendered in turn, so each frame's speedup pairs two measurements
// taken moments apart.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "demo/glfw_window.h"
#include "tool/tool_run.h"

namespace spire::demo {

struct LodRunOptions {
  std::string scenePath;
  std::string outputDir;
  uint32_t warmup = 1;    // frames of each configuration rendered first, at the path's start
  uint32_t measured = 1;  // frames along the loop through the scene's views
  std::optional<uint32_t> windowFrames;
};

// `run` has loaded the scene's policy and started its renderer. Headless:
// measures, writes full_quality.png, lod.png, comparison.png and
// report.md into the output directory as a set, and prints the summary line.
// With `window`, flies through the scene instead (keys 1-3 switch). Returns
// the exit status.
int runLodDemo(const LodRunOptions& options, engine::ToolRun& run, GlfwWindow* window, std::ostream& out);

}  // namespace spire::demo

// spire-explore on a scene with "lod" (docs/explorer.md, "Level-of-detail
// policy"): the scene drawn with level of detail by spire-demo's LodScene,
// the camera at a chosen frame of the scene's fly-through, and the policy's
// editor: which group member draws each distance band (the member is how a
// policy assigns a set of decisions to a band: each member is a base shader
// with its own placements and locks), where each band ends, hysteresis and
// cross-fade length, with undo. New edges draw at once; new members (or
// bands) compile on a worker while the previous levels keep drawing; an edit
// the policy reader rejects is shown with its diagnostics while the last
// valid policy keeps drawing; Save writes the policy file.
#pragma once

#include <ostream>

#include "demo/glfw_window.h"
#include "explore/explorer.h"
#include "tool/tool_run.h"

namespace spire::explore {

// `run` has loaded the scene and its policy and started its renderer.
// Returns the exit status.
int runLodExplorer(const ExploreOptions& options, engine::ToolRun& run, demo::GlfwWindow& window, std::ostream& out);

}  // namespace spire::explore

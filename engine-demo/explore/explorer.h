// spire-explore: the paper's rapid exploration (section 7.1, Figure 6) as a
// window. The selected instance's choices are listed with what propagation
// still allows; each change compiles in process on a worker thread through
// the compiler's one compile entry point while the previous variant keeps
// rendering, and the new variant's frame time, error against a reference and
// NaN/Inf count appear as soon as it is on screen, with where the time of the
// change went. A spire-tune output directory shows as a Pareto view whose
// points apply their decisions. A script drives the same loop for tests and
// benchmarks.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "demo/glfw_window.h"
#include "tool/tool_run.h"

namespace spire::explore {

struct ExploreOptions {
  std::string scenePath;
  size_t instance = 0;  // whose shader's choices are explored
  // Decision files: the reference the error is measured against, and the
  // decisions the session starts from. Default for both: the scene's first
  // variant, else the instance's own decisions.
  std::optional<std::filesystem::path> reference;
  std::optional<std::filesystem::path> decisions;
  std::string saveTo;  // where the Save button and `save` without a path write
  std::optional<std::filesystem::path> script;
  std::optional<std::filesystem::path> log;      // each change's timing, as JSON
  std::optional<uint64_t> maxFrames;             // close after this many frames
  std::optional<std::filesystem::path> tuneDir;  // a spire-tune output directory for the Pareto view
};

// Runs the explorer on `run`'s scene and renderer, presenting to `window`
// (whose surface `run`'s context was made with). Returns the exit status.
int runExplorer(const ExploreOptions& options, engine::ToolRun& run, demo::GlfwWindow& window, std::ostream& out);

}  // namespace spire::explore

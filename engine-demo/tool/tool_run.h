// One run of an engine tool (spire-demo, spire-tune) up to the point where
// the tool's own work starts: the scene file loaded with its diagnostics
// printed the compiler's way, the Vulkan context, and the renderer over both;
// and at the end, the run failed on any validation message. Both tools set
// up the same way, so a scene, a device option or a validation message means
// the same in each.
//
// Each step returns nullopt to go on, or the exit status to return after it
// printed why (the convention of parseToolArguments).
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "lod/lod_policy.h"
#include "renderer/scene_renderer.h"
#include "scene/scene_file.h"
#include "support/diagnostic.h"
#include "support/source_manager.h"
#include "tool/engine_options.h"
#include "tool/error_report.h"
#include "vk/context.h"

namespace spire::engine {

// The device options every engine tool takes (--device, --validation).
struct DeviceOptions {
  std::string filter;  // a substring of the device name; empty: llvmpipe
  bool validation = false;
  // What a window needs: its surface extensions and its surface (demo --window).
  std::vector<std::string> instanceExtensions;
  vk::SurfaceFactory surfaceFactory;
};

class ToolRun {
 public:
  // `tool` names the program in messages and to the Vulkan driver. Fixes the
  // host allocator first (renderer/host_allocator.h), before any Vulkan work.
  ToolRun(std::string tool, std::ostream& err);
  ToolRun(const ToolRun&) = delete;
  ToolRun& operator=(const ToolRun&) = delete;

  // Exit 1 after printing the scene's diagnostics. `resolution` replaces the
  // scene's own (--resolution).
  std::optional<int> loadScene(const std::string& path, std::optional<ImageSize> resolution = std::nullopt);
  // The scene's level-of-detail policy ("lod"); exit 1 after printing its
  // diagnostics, or when the scene has none.
  std::optional<int> loadLodPolicy();
  // Exit 3 (kExitNoDevice) when no usable device can be opened.
  std::optional<int> openDevice(const DeviceOptions& options);
  // The renderer of the loaded scene on the opened device.
  SceneRenderer& startRenderer(uint32_t defaultBakeSize);
  // `status`, unless validation reported anything (then those messages and
  // kExitInputError).
  int finish(int status) const;

  const scene::SceneFile& scene() const { return *scene_; }
  const lod::LodPolicy& lodPolicy() const { return *policy_; }
  const vk::Context& context() const { return *context_; }
  SceneRenderer& renderer() { return *renderer_; }
  DiagnosticList& diagnostics() { return diags_; }
  // The sources diagnostics are rendered with: a tool adds the other files it
  // reads (a script, a decision file) here so their errors print the same way.
  SourceManager& sources() { return sources_; }
  const SourceManager& sources() const { return sources_; }
  ErrorReporter& reporter() { return reporter_; }
  // Adds `diagnostics`, which a worker thread collected in a list of its own
  // (it cannot report into this one while this thread may), and returns
  // them rendered.
  std::string adoptDiagnostics(std::vector<Diagnostic> diagnostics);
  // The diagnostics reported since the list had `mark` of them, rendered.
  std::string renderSince(size_t mark) const;
  // Prints `error` after any pending diagnostics; returns kExitInputError.
  int fail(const Error& error) { return reporter_.fail(error); }

 private:
  std::string tool_;
  std::ostream& err_;
  SourceManager sources_;
  DiagnosticList diags_;
  ErrorReporter reporter_;
  std::optional<scene::SceneFile> scene_;
  std::optional<lod::LodPolicy> policy_;
  // Declared before the renderer, which must be destroyed first.
  std::optional<vk::Context> context_;
  std::optional<SceneRenderer> renderer_;
};

}  // namespace spire::engine

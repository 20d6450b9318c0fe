// spire-explore's level-of-detail mode makes the scene of an edited policy
// on a worker thread: it compiles the levels (every instance's shader as
// each member), as decision changes compile on LiveCompiler's, then runs
// their bakes and builds their pipelines (LodScene::createCompiled, which
// may run beside the frame loop's draws of the previous scene). So the
// window keeps drawing the previous levels until the new scene is ready. Only
// the latest request matters: one submitted while another is being made
// waits, replacing any that waited before it.
#pragma once

#include <cstdint>
#include <functional>
#include <future>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "driver/shader_library.h"
#include "lod/lod_policy.h"
#include "renderer/lod_scene.h"
#include "support/diagnostic.h"

namespace spire::explore {

class LevelCompiler {
 public:
  using Programs = engine::LodScene::LevelPrograms;
  using Scene = std::unique_ptr<engine::LodScene>;
  // Both run on the worker thread, one request at a time, and must not use
  // anything the caller's thread uses meanwhile, except what Vulkan and the
  // renderer allow beside draws (vk::Context::submitAndWait,
  // SceneRenderer::prepare with TargetUse::Keep).
  using CompileFunction = std::function<engine::Expected<Programs>(const lod::LodPolicy&)>;
  // `prepare` reports into the list it is given, of the worker's own.
  using PrepareFunction = std::function<engine::Expected<Scene>(const lod::LodPolicy&, Programs, DiagnosticList&)>;

  struct Outcome {
    uint64_t request = 0;
    lod::LodPolicy policy;  // the one submitted
    // The scene, or why there is none. (Not an Expected: GCC 12 warns of a
    // delete of an unallocated object in its destructor inlined here.)
    Scene scene;
    std::optional<engine::Error> error;
    double compileMs = 0.0;  // the compile, on the worker
    double prepareMs = 0.0;  // the bakes and pipelines, on the worker; 0 when the compile failed
    // What the prepare reported, for the caller's thread to add to its list.
    std::vector<Diagnostic> diagnostics;
  };

  LevelCompiler(CompileFunction compile, PrepareFunction prepare)
      : compile_(std::move(compile)), prepare_(std::move(prepare)) {}
  LevelCompiler(const LevelCompiler&) = delete;
  LevelCompiler& operator=(const LevelCompiler&) = delete;
  // Waits for a compile in progress (a queued one is dropped).
  ~LevelCompiler() = default;

  // Makes `policy`'s scene, now or once the one in progress is done.
  void submit(uint64_t request, lod::LodPolicy policy);
  // The newest finished scene, without waiting: nullopt while one is in
  // progress, and for one that a queued request replaced (which starts now).
  std::optional<Outcome> poll();
  // Whether a request is queued or compiling.
  bool busy() const { return running_.valid() || queued_.has_value(); }

 private:
  void launch(uint64_t request, lod::LodPolicy policy);

  CompileFunction compile_;
  PrepareFunction prepare_;
  std::optional<std::pair<uint64_t, lod::LodPolicy>> queued_;
  std::future<Outcome> running_;  // last: its destructor waits for the worker, which uses compile_ and prepare_
};

// The worker's compile for `renderer`'s scene: instance p's shader as each
// member, `Rock<LodMQ>`, in `libraries[p]` (the renderer's own, which the
// caller's thread must not compile in meanwhile), with the instance's own
// decisions. Programs are kept by instance and member, so a level whose
// member compiled before costs nothing.
LevelCompiler::CompileFunction compileLevelsIn(const engine::SceneRenderer& renderer,
                                               std::vector<ShaderLibrary*> libraries);

}  // namespace spire::explore

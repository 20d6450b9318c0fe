// spire-explore's level-of-detail mode compiles the levels of an edited
// policy (every instance's shader as each member) on a worker thread, as
// decision changes compile on LiveCompiler's, so the window keeps drawing
// the previous levels while a new member compiles. Only the latest request
// matters: one submitted while another compiles waits, replacing any that
// waited before it. The bakes and pipelines of the new levels are made on
// the caller's thread (LodScene::createCompiled), since they use Vulkan.
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

namespace spire::explore {

class LevelCompiler {
 public:
  using Programs = engine::LodScene::LevelPrograms;
  // Runs on the worker thread, one request at a time: it must not touch
  // Vulkan or anything the caller's thread uses meanwhile.
  using CompileFunction = std::function<engine::Expected<Programs>(const lod::LodPolicy&)>;

  struct Outcome {
    uint64_t request = 0;
    lod::LodPolicy policy;  // the one submitted
    engine::Expected<Programs> programs = engine::Error{"not compiled"};
    double milliseconds = 0.0;  // the compile alone, on the worker
  };

  explicit LevelCompiler(CompileFunction compile) : compile_(std::move(compile)) {}
  LevelCompiler(const LevelCompiler&) = delete;
  LevelCompiler& operator=(const LevelCompiler&) = delete;
  // Waits for a compile in progress (a queued one is dropped).
  ~LevelCompiler() = default;

  // Compiles `policy`'s levels, now or once the compile in progress is done.
  void submit(uint64_t request, lod::LodPolicy policy);
  // The newest finished compile, without waiting: nullopt while one is in
  // progress, and for one that a queued request replaced (which starts now).
  std::optional<Outcome> poll();
  // Whether a request is queued or compiling.
  bool busy() const { return running_.valid() || queued_.has_value(); }

 private:
  void launch(uint64_t request, lod::LodPolicy policy);

  CompileFunction compile_;
  std::optional<std::pair<uint64_t, lod::LodPolicy>> queued_;
  std::future<Outcome> running_;  // last: its destructor waits for the worker, which uses compile_
};

// The worker's compile for `renderer`'s scene: instance p's shader as each
// member, `Rock<LodMQ>`, in `libraries[p]` (the renderer's own, which the
// caller's thread must not compile in meanwhile), with the instance's own
// decisions. Programs are kept by instance and member, so a level whose
// member compiled before costs nothing.
LevelCompiler::CompileFunction compileLevelsIn(const engine::SceneRenderer& renderer,
                                               std::vector<ShaderLibrary*> libraries);

}  // namespace spire::explore

// Compiles the explorer's variants on a worker thread, and prepares the
// scene that draws them there too (bakes and pipelines), so the window keeps
// drawing the previous variant until the next one is ready to draw. Only the
// latest request matters: one that arrives while another is being made
// replaces any request still waiting, and results come back tagged with
// their request.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "driver/shader_library.h"
#include "renderer/error.h"
#include "renderer/scene_renderer.h"
#include "renderer/variant_program.h"
#include "support/diagnostic.h"

namespace spire::explore {

using Placement = std::map<std::string, std::string>;

struct CompileJob {
  uint64_t request = 0;
  Placement placement;
  ShaderLibrary::Attributes attributes;
  bool reload = false;  // read the sources again first (one of them was saved)
  // Every instance's program as drawn now: the scene prepared is these with
  // the explored instance's replaced by the new variant.
  std::vector<engine::VariantProgram> programs;
};

struct CompileOutcome {
  uint64_t request = 0;
  // After a reload that succeeded: the library the variant was compiled in,
  // which later compiles use too.
  std::shared_ptr<ShaderLibrary> library;
  engine::Expected<engine::VariantProgram> program = engine::Error{"not compiled"};
  std::vector<std::string> skipped;  // decisions the compiler did not apply
  double milliseconds = 0.0;         // on the worker: the compile, and the prepare when there is one
  // After a compile that succeeded: the scene drawing the variant, or why
  // there is none, and what preparing it reported (for the caller's thread
  // to add to its list: the worker's were reported into a list of its own).
  std::optional<engine::Expected<engine::PreparedScene>> prepared;
  std::vector<Diagnostic> diagnostics;
  double prepareMs = 0.0;  // the prepare alone
};

class LiveCompiler {
 public:
  // `compile` runs on the worker thread, one request at a time: it must not
  // use anything the caller's thread uses meanwhile, except what Vulkan and
  // the renderer allow beside draws (vk::Context::submitAndWait,
  // SceneRenderer::prepare with TargetUse::Keep and a diagnostic list of its
  // own). Fills the outcome but for its request and compile time.
  using CompileFunction = std::function<void(const CompileJob&, CompileOutcome&)>;

  explicit LiveCompiler(CompileFunction compile);
  LiveCompiler(const LiveCompiler&) = delete;
  LiveCompiler& operator=(const LiveCompiler&) = delete;
  // Waits for a compile in progress, then stops the worker.
  ~LiveCompiler();

  // Queues `job` (requests increase), replacing a queued one; a reload
  // asked for by the replaced job is kept.
  void submit(CompileJob job);
  // A finished compile, if there is one, without waiting.
  std::optional<CompileOutcome> poll();
  // Whether a request is queued or compiling.
  bool busy() const;

 private:
  void run();

  CompileFunction compile_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<CompileJob> queued_;
  std::vector<CompileOutcome> done_;
  bool compiling_ = false;
  bool stopping_ = false;
  std::thread worker_;  // last: started after the members it uses
};

}  // namespace spire::explore

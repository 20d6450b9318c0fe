// Compiles the explorer's variants on a worker thread, so the window keeps
// drawing the previous variant while the next one compiles. Only the latest
// request matters: one that arrives while another compiles replaces any
// request still waiting, and results come back tagged with their request.
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
#include "renderer/variant_program.h"

namespace spire::explore {

using Placement = std::map<std::string, std::string>;

struct CompileJob {
  uint64_t request = 0;
  Placement placement;
  ShaderLibrary::Attributes attributes;
  bool reload = false;  // read the sources again first (one of them was saved)
};

struct CompileOutcome {
  uint64_t request = 0;
  // After a reload that succeeded: the library the variant was compiled in,
  // which later compiles use too.
  std::shared_ptr<ShaderLibrary> library;
  engine::Expected<engine::VariantProgram> program = engine::Error{"not compiled"};
  std::vector<std::string> skipped;  // decisions the compiler did not apply
  double milliseconds = 0.0;         // the compile alone, on the worker
};

class LiveCompiler {
 public:
  // `compile` runs on the worker thread: it must not touch Vulkan or
  // anything the caller's thread uses meanwhile.
  // Fills the outcome's library, program and skipped decisions.
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

// What the explorer keeps per explored instance of the scene, so that the
// window can switch to another instance and back (the Choices panel's
// instance list, the script's `instance N`) and find it as it was: the
// shader's choices and decisions with their undo history, the worker that
// compiles the instance's variants, the sources it watches, and a spire-tune
// run loaded for its shader. The variant each instance draws is the
// explorer's, in its programs per instance.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "explore/decision_state.h"
#include "explore/live_compiler.h"
#include "explore/source_watch.h"
#include "explore/tune_results.h"

namespace spire::explore {

struct InstanceSession {
  size_t instance = 0;
  std::string shader;
  std::optional<DecisionState> state;  // over a choice space of a library the explorer keeps
  std::unique_ptr<LiveCompiler> compiler;
  SourceWatch watch;
  std::optional<TuneResults> tune;  // --tune-dir or load-tune, for this instance's shader
};

}  // namespace spire::explore

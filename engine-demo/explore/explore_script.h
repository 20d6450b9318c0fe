// spire-explore --script: the explorer driven by a file of actions instead
// of a person, for tests and benchmarks (docs/explorer.md, "Scripts"). One
// action per line; `#` or `//` starts a comment:
//
//   set Terrain.albedo = PrebakeTex   decide a choice (or `set albedo = ...`)
//   unset Terrain.albedo              back to the compiler's default
//   reset                             drop every decision
//   load FILE / save FILE             a decision file (relative to the script)
//   undo                              the decisions before the last change
//   walk N SEED                       N random single-decision changes, each to
//                                     an alternative still possible (benchmarks)
//   view variant|reference|error|hazards|split
//   wait-frames N                     present N frames
//   wait-reload                       until a saved source was read again (or failed to compile)
//   screenshot FILE                   what the view shows at the fixed camera, as PNG
//   screenshot-window FILE            the next frame as the window shows it, panels included
//   load-tune DIR                     a spire-tune output directory, for the Pareto view
//   apply-front K                     the decisions of the front's K-th point (from 0, fastest first)
//   instance N                        explore the scene's instance N (from 0); each keeps its decisions
//   quit
//
// Each action that changes the decisions finishes when the new variant is on
// screen (or its compile failed), so the next action sees it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::explore {

enum class ActionKind {
  Set,
  Unset,
  Reset,
  Load,
  Save,
  Undo,
  Walk,
  View,
  WaitFrames,
  WaitReload,
  Screenshot,
  WindowShot,
  LoadTune,
  ApplyFront,
  Instance,
  Quit
};

struct ScriptAction {
  ActionKind kind = ActionKind::Quit;
  std::string target;  // the choice (set, unset), file (load, save, screenshot), folder (load-tune) or view mode
  std::string value;   // the placement (set)
  uint32_t count = 0;  // wait-frames, walk, apply-front, instance
  uint64_t seed = 0;   // walk
  SourceRange range;   // the whole line, for errors while running it
};

// The actions of `file` in order; malformed lines are E7201 errors with the
// line and column (every line is checked), and then no action is returned.
std::vector<ScriptAction> parseScript(const SourceManager& sources, FileId file, DiagnosticList& diags);

// The action's text as written, for logs ("set Terrain.albedo = PrebakeTex").
std::string describeAction(const SourceManager& sources, const ScriptAction& action);

}  // namespace spire::explore

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
// On a level-of-detail scene (docs/explorer.md, "Level-of-detail policy"),
// the policy's edits instead of decisions, with screenshot,
// screenshot-window, wait-frames and quit:
//
//   policy until LEVEL DIST           level LEVEL's band ends at DIST
//   policy member LEVEL NAME          level LEVEL draws with the group member NAME
//   policy hysteresis X / policy transition N
//   policy add NAME DIST              a band of NAME ending at DIST
//   policy remove LEVEL
//   policy save [FILE]                the policy file (default: the scene's, or --save-to)
//   policy undo / policy redo         the policy before the last edit / the undone edit again
//   fly-frame N                       the camera at frame N of the scene's fly-through
//
// Each action that changes the decisions finishes when the new variant is on
// screen (or its compile failed), so the next action sees it; so does a
// policy edit that makes new levels.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "support/diagnostic.h"
#include "support/expected.h"
#include "support/source_manager.h"
#include "tool/tool_run.h"

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
  Quit,
  PolicyUntil,
  PolicyMember,
  PolicyHysteresis,
  PolicyTransition,
  PolicyAdd,
  PolicyRemove,
  PolicySave,
  PolicyUndo,
  PolicyRedo,
  FlyFrame
};

// Whether the action is one of a level-of-detail scene's (policy, fly-frame).
bool isLodAction(ActionKind kind);

struct ScriptAction {
  ActionKind kind = ActionKind::Quit;
  std::string target;   // the choice (set, unset), file (load, save, screenshot), folder (load-tune) or view mode
  std::string value;    // the placement (set), the member (policy member, policy add)
  uint32_t count = 0;   // wait-frames, walk, apply-front, instance; the level or frame count of policy edits, fly-frame
  double number = 0.0;  // the distance or hysteresis of policy edits
  uint64_t seed = 0;    // walk
  SourceRange range;    // the whole line, for errors while running it
};

// The actions of `file` in order; malformed lines are E7201 errors with the
// line and column (every line is checked), and then no action is returned.
std::vector<ScriptAction> parseScript(const SourceManager& sources, FileId file, DiagnosticList& diags);

// Reads the script file at `path` into `actions`: nullopt to go on, or the
// exit status after `run` printed why (it cannot be read, or has errors).
std::optional<int> loadScriptFile(engine::ToolRun& run, const std::filesystem::path& path,
                                  std::vector<ScriptAction>& actions);

// An action that cannot be carried out: E7202 at its line, printed now.
void reportScriptError(engine::ToolRun& run, const ScriptAction& action, const std::string& message);

// A path a script names, relative to the script's folder (as given when
// there is no script: from the window's buttons).
std::filesystem::path scriptRelative(const std::optional<std::filesystem::path>& script, const std::string& path);

// The action's text as written, for logs ("set Terrain.albedo = PrebakeTex").
std::string describeAction(const SourceManager& sources, const ScriptAction& action);

// --log FILE: `document` as indented JSON, written atomically. The actions
// in it are a script's words, any bytes: what is not UTF-8, which JSON
// cannot hold, is written as U+FFFD rather than thrown on.
Expected<void, Failure> writeSessionLog(const std::filesystem::path& path, const nlohmann::ordered_json& document);

}  // namespace spire::explore

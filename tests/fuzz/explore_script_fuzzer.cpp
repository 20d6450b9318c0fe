// libFuzzer target for spire-explore scripts: the input bytes are the text of
// one script. It is parsed (every malformed line must be an error with a
// place, and a script with errors yields no actions), and its decision
// actions (set, unset, reset, undo, walk) are carried out on the explorer's
// decisions over an example shader (fuzz_support.h: every examples/*.spire in
// one library). Whatever the explorer accepts must build a variant with every
// decision applied: that is what it promises when it shows an alternative as
// possible, so a skipped decision aborts. Its policy edits are carried out
// on the LOD policy editor: a policy the editor calls valid must be a file
// that reads back to itself, and the last valid one must stay one; an undo
// that is made can be redone to the same policy, and undone again.
//
// Built two ways (see CMakeLists.txt beside this file):
//   spire_explore_script_fuzzer  clang + -fsanitize=fuzzer,address,undefined (fuzz preset)
//   spire_explore_script_replay  any compiler, with replay_main.cpp: the CTest
//                                FuzzExploreScriptCorpusRegression over corpus_explore/
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include "explore/decision_state.h"
#include "explore/explore_script.h"
#include "explore/policy_editor.h"
#include "fuzz/fuzz_support.h"

namespace {

using spire::explore::ActionKind;
using spire::explore::DecisionState;
using spire::explore::ScriptAction;

constexpr uint32_t kMaxWalk = 8;  // steps per walk action: each step propagates every alternative

void walk(DecisionState& state, const ScriptAction& action) {
  std::mt19937_64 random(action.seed);
  for (uint32_t i = 0; i < std::min(action.count, kMaxWalk); ++i) {
    std::vector<std::pair<std::string, std::string>> candidates;
    for (const auto& row : state.rows()) {
      for (const auto& alt : row.alternatives) {
        if (alt.possible) candidates.emplace_back(row.key, alt.placement);
      }
    }
    if (candidates.empty()) return;
    const auto& [key, placement] = candidates[random() % candidates.size()];
    if (!state.set(key, placement)) std::abort();  // offered as possible, then refused
  }
}

void apply(DecisionState& state, const ScriptAction& action) {
  switch (action.kind) {
    case ActionKind::Set: (void)state.set(action.target, action.value); break;
    case ActionKind::Unset: (void)state.unset(action.target); break;
    case ActionKind::Reset: (void)state.replace({}); break;
    case ActionKind::Undo: (void)state.undo(); break;
    case ActionKind::Walk: walk(state, action); break;
    default: break;
  }
}

// Writes the policy, reads it back and writes that again: the same text.
bool readsBack(const spire::lod::LodPolicy& policy) {
  spire::SourceManager sources;
  spire::DiagnosticList diags;
  const std::string text = spire::lod::formatLodPolicy(policy);
  const auto read = spire::lod::parseLodPolicy("policy.json", text, sources, diags);
  return read && spire::lod::formatLodPolicy(*read) == text;
}

// Undo, checked by redoing and undoing it again: each gives back its text.
void undo(spire::explore::PolicyEditor& editor) {
  const std::string before = editor.text();
  if (!editor.undo()) return;
  const std::string after = editor.text();
  if (!editor.redo() || editor.text() != before) std::abort();
  if (!editor.undo() || editor.text() != after) std::abort();
}

void edit(spire::explore::PolicyEditor& editor, const ScriptAction& action) {
  const auto level = static_cast<size_t>(action.count);
  const auto number = static_cast<float>(action.number);
  switch (action.kind) {
    case ActionKind::PolicyUntil: (void)editor.setUntil(level, number); break;
    case ActionKind::PolicyMember: (void)editor.setMember(level, action.value); break;
    case ActionKind::PolicyHysteresis: editor.setHysteresis(number); break;
    case ActionKind::PolicyTransition: editor.setTransitionFrames(action.count); break;
    case ActionKind::PolicyAdd: editor.addLevel(action.value, number); break;
    case ActionKind::PolicyRemove: (void)editor.removeLevel(level); break;
    case ActionKind::PolicyUndo: undo(editor); break;
    case ActionKind::PolicyRedo: (void)editor.redo(); break;
    default: return;
  }
  if (editor.isValid() && !readsBack(editor.edited())) std::abort();
  if (!readsBack(editor.valid())) std::abort();
}

spire::lod::LodPolicy startPolicy() {
  spire::lod::LodPolicy policy;
  policy.levels = {
      {"LodHQ", 12.0F, {}, {}}, {"LodMQ", 35.0F, {}, {}}, {"LodLQ", std::numeric_limits<float>::infinity(), {}, {}}};
  return policy;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace spire;
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile("fuzz.explore", std::string(reinterpret_cast<const char*>(data), size));
  const std::vector<ScriptAction> actions = explore::parseScript(sources, file, diags);
  if (diags.hasErrors() && !actions.empty()) std::abort();  // a script with errors runs nothing
  // Every script error has its place, but the one that says the error limit
  // is reached (E2005), which is about the whole script.
  for (const Diagnostic& d : diags.all()) {
    if (!d.range.valid() && d.code != DiagCode::E2005) std::abort();
  }
  ShaderLibrary& library = fuzz::exampleLibrary();
  const std::vector<std::string> shaders = library.shaderNames();
  if (shaders.empty() || actions.empty()) return 0;
  const std::string& shader = shaders[size % shaders.size()];
  DecisionState state(*library.choiceSpace(shader));
  explore::PolicyEditor policy(startPolicy());
  for (const ScriptAction& action : actions) {
    (void)explore::describeAction(sources, action);
    apply(state, action);
    edit(policy, action);
    std::vector<std::string> skipped;
    if (!library.buildVariant(shader, state.decisions(), &skipped) || !skipped.empty()) std::abort();
  }
  return 0;
}

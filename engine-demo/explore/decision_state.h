// The explorer's decisions for one shader: what the user decided so far, the
// choices the compiler library enumerates for the shader, and which of their
// alternatives constraint propagation still allows given those decisions
// (paper section 5.3), so the explorer can show impossible alternatives as
// such instead of letting the user pick them. Every change can be undone.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "driver/shader_library.h"
#include "graph/choice_space.h"
#include "support/expected.h"

namespace spire::explore {

// One alternative of a choice as the explorer shows it.
struct Alternative {
  std::string placement;  // "World" or "World:variation"
  bool possible = true;   // still allowed after propagating the decisions
};

// One choice of the shader with the state of its alternatives.
struct ChoiceRow {
  std::string key;        // "Terrain.albedo", as decision files spell it
  std::string component;  // "albedo"
  std::vector<Alternative> alternatives;
  std::optional<std::string> decided;  // the user's decision, if any
};

class DecisionState {
 public:
  // `space` (the shader's, from ShaderLibrary::choiceSpace) must outlive
  // this.
  explicit DecisionState(const graph::ChoiceSpace& space);

  // Whether `name` ("Terrain.albedo" or "albedo") is a choice of the shader.
  bool isChoice(const std::string& name) const { return findChoice(name) != nullptr; }
  // Forgets every change that could be undone (the start of a session).
  void clearHistory() { undo_.clear(); }

  // component -> placement, keyed by component name as the compiler
  // library's in-memory decisions are (SceneRenderer::compileVariant).
  const std::map<std::string, std::string>& decisions() const { return current_.placement; }
  // Attributes a loaded decision file gave its decisions (`[Format: "RGBA8"]`),
  // kept while the decision stands: a bake's format and size change the image.
  const ShaderLibrary::Attributes& attributes() const { return current_.attributes; }
  // Every choice with the alternatives set() would accept now; cached until
  // the decisions change (the panels ask every frame).
  std::vector<ChoiceRow> rows() const;

  // Decides `choice` ("Terrain.albedo" or "albedo") = `placement`. The error
  // says why when the choice is unknown, the placement is not one of its
  // alternatives, or propagation already ruled it out.
  Expected<void, Failure> set(const std::string& choice, const std::string& placement);
  // Drops the decision on `choice`, leaving it to the compiler's default.
  Expected<void, Failure> unset(const std::string& choice);
  // Replaces every decision at once (a loaded decision file, with the
  // attributes of its lines).
  Expected<void, Failure> replace(const std::map<std::string, std::string>& decisions,
                                  const ShaderLibrary::Attributes& attributes = {});
  // Restores the decisions before the last change; false when there is none.
  bool undo();

  // The decisions as a decision file (graph::writeDecisionFile).
  std::string decisionFileText(std::string_view comment) const;

 private:
  const graph::Choice* findChoice(const std::string& name) const;
  // The space with `decisions` applied; nullopt when they contradict.
  std::optional<graph::ChoiceSpace> propagated(const std::map<std::string, std::string>& decisions) const;
  // "; change or unset mixFactor (now Fragment)": the decisions in
  // `decisions` whose removal alone makes them consistent again, besides
  // `changed`'s; empty when no single one does.
  std::string blockers(const std::map<std::string, std::string>& decisions, const std::string& changed) const;
  struct Decided {
    std::map<std::string, std::string> placement;
    ShaderLibrary::Attributes attributes;
  };
  Expected<void, Failure> commit(Decided next);

  const graph::ChoiceSpace* space_;
  std::vector<graph::Choice> choices_;
  Decided current_;
  std::vector<Decided> undo_;
  mutable std::optional<std::vector<ChoiceRow>> rows_;
};

}  // namespace spire::explore

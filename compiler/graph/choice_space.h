// Constraint propagation over a shader graph (paper section 5.3): which
// alternatives can still be part of a valid variant, given the decisions made
// so far. The choice file is this space before any decision.
#pragma once

#include <string>
#include <vector>

#include "graph/shader_graph.h"

namespace spire::graph {

// The alternatives still possible for each component. Propagation removes
// an alternative when
//  - one of its dependencies has no remaining alternative in a world that
//    reaches the alternative's world, or
//  - a consumer that is certainly live (an export, a strategy argument, or
//    a dependency of every remaining alternative of such a consumer) has no
//    remaining alternative in a world the alternative's world reaches.
// Both rules only remove alternatives that no valid variant can use.
class ChoiceSpace {
 public:
  // All alternatives of the graph, propagated.
  explicit ChoiceSpace(const ShaderGraph& graph);

  const ShaderGraph& graph() const { return *graph_; }
  bool alive(sem::ComponentId c, AltId a) const { return alive_[c][a] != 0; }
  std::vector<AltId> aliveAlternatives(sem::ComponentId c) const;
  uint32_t aliveCount(sem::ComponentId c) const;
  // Live in every variant (exports, strategy arguments, and what they need).
  bool isMandatory(sem::ComponentId c) const { return mandatory_[c]; }
  // Live in at least one variant: reachable from the pipeline's requirements.
  std::vector<bool> possiblyLive() const;

  // Keeps only `alt` for `c` and propagates. False when that leaves a
  // mandatory component without alternatives (the space is then unusable).
  bool restrict(sem::ComponentId c, AltId alt);
  bool consistent() const { return consistent_; }

 private:
  bool propagate();
  bool forwardPass();
  bool backwardPass();
  void kill(sem::ComponentId c, AltId a, bool& changed);
  WorldMask worldsOf(sem::ComponentId c) const;

  const ShaderGraph* graph_;
  std::vector<std::vector<uint8_t>> alive_;
  std::vector<WorldMask> available_;  // worlds reachable from a remaining alternative
  std::vector<bool> mandatory_;
  bool consistent_ = true;
};

// One choice: a possibly-live, computed component with more than one
// remaining alternative.
struct Choice {
  sem::ComponentId component = 0;
  std::string key;                  // "Terrain.albedo"
  std::vector<AltId> alternatives;  // remaining, in choice-file order
  std::vector<std::string> names;   // "PrebakeTex", "Vertex:basic", ...
};

// The choices of the space, in declaration order.
std::vector<Choice> enumerateChoices(const ChoiceSpace& space);

// One line per choice: `Prefix.component = {World[:variation],...}`.
std::string writeChoiceFile(const ChoiceSpace& space);

// The choice file of several shaders. A key shared by shaders (an inherited
// component, prefixed by its base) appears once, at its first place, with
// the alternatives every one of those shaders allows, so that one decision
// applies to all of them; each alternative only some allow gets a comment
// line above it naming them (`// PrebakeTex is possible only for A, B`).
std::string writeChoiceFile(const std::vector<const ChoiceSpace*>& spaces);

}  // namespace spire::graph

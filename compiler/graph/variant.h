// Shader variants (paper sections 4.4 and 5.3): one alternative for every
// live component, from decisions applied greedily and default placement for
// the rest, plus what each world computes, imports and exports.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "graph/choice_space.h"

namespace spire::graph {

// A requested placement: component `component` takes alternative `alternative`.
struct DecisionRequest {
  sem::ComponentId component = 0;
  AltId alternative = 0;
  // Data-layout and other per-component hints carried to code generation
  // (`[Format: "RGB10_A2"]`, `[TextureSize: "512"]`).
  std::vector<std::pair<std::string, std::string>> attributes;
  // How many finalizers the shader that decides is below (lockDepth): a
  // decision counts where a base places what its locked worlds see only
  // when a shader at or above that base's finalizer makes it. In-memory
  // decisions, which name no shader, are the base's.
  uint32_t lockDepth = 0;
};

enum class DecisionStatus : uint8_t {
  Applied,
  NotAChoice,  // the alternative was pruned: no valid variant can use it
  Conflict,    // incompatible with an earlier applied decision
};

struct DecisionOutcome {
  DecisionStatus status = DecisionStatus::Applied;
  size_t conflictsWith = 0;  // index of the earlier request, for Conflict
};

// A value crossing from one world to the next through an import.
struct Transfer {
  sem::ComponentId component = 0;
  uint32_t importIndex = 0;  // into Pipeline::imports
};

struct WorldPlan {
  std::vector<sem::ComponentId> computed;  // live definitions here, dependency order
  std::vector<Transfer> inputs;            // imported into this world
  std::vector<Transfer> outputs;           // exported from this world
};

class Variant;
struct VariantResult;
class ChoiceSpace;
VariantResult buildVariant(const ChoiceSpace& space, const std::vector<DecisionRequest>& requests);

class Variant {
 public:
  const ShaderGraph& graph() const { return *graph_; }
  // The chosen alternative of a live component; nullopt for dead ones.
  const std::optional<AltId>& choice(sem::ComponentId c) const { return choice_[c]; }
  // Live components in dependency order.
  const std::vector<sem::ComponentId>& live() const { return live_; }
  const WorldPlan& world(sem::WorldId w) const { return worlds_[w]; }
  const std::vector<std::pair<std::string, std::string>>& attributes(sem::ComponentId c) const;
  sem::WorldId worldOf(sem::ComponentId c) const { return graph_->node(c).alternatives[*choice_[c]].world; }

  // The placement as a decision file: one line per live, non-input
  // component. Applying it reproduces this variant exactly.
  std::string placementText() const;
  // placementText() plus, per world, what it computes, imports and exports.
  std::string describe() const;
  // The route of every value that crosses worlds: "// name: A -> B -> C
  // (strategy transfer, ...)", one line per value.
  std::string describeRoutes() const;

 private:
  friend class VariantBuilder;
  friend VariantResult buildVariant(const ChoiceSpace& space, const std::vector<DecisionRequest>& requests);
  const ShaderGraph* graph_ = nullptr;
  std::vector<std::optional<AltId>> choice_;
  std::vector<sem::ComponentId> live_;
  std::vector<WorldPlan> worlds_;
  std::map<sem::ComponentId, std::vector<std::pair<std::string, std::string>>> attributes_;
};

struct VariantResult {
  std::optional<Variant> variant;         // empty only if no valid variant exists at all
  std::vector<DecisionOutcome> outcomes;  // one per request
};

// Applies `requests` in order, skipping any that is not a choice or that
// conflicts with those already applied; places every other live component
// in its latest feasible world (first declared variation on ties). The
// space is the shader's initial choice space and is not modified.
VariantResult buildVariant(const ChoiceSpace& space, const std::vector<DecisionRequest>& requests);

}  // namespace spire::graph

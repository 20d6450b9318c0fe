// The shader graph of one concrete shader (paper section 5.2): every
// component with all its concrete alternatives, i.e. each declared definition
// instantiated in each world where it can be computed.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sema/semantic_model.h"
#include "support/diagnostic.h"

namespace spire::graph {

using AltId = uint32_t;
// Sets of worlds as bit masks; pipelines have at most 64 worlds.
using WorldMask = uint64_t;
inline constexpr uint32_t kMaxWorlds = 64;

struct Alternative {
  sem::WorldId world = 0;
  uint32_t variation = 0;  // index into ComponentNode::variations
  const sem::Definition* definition = nullptr;
};

struct ComponentNode {
  sem::ComponentId id = 0;
  const sem::Component* component = nullptr;
  // The prefix in choice and decision files: the shader that defines the
  // component, or the base it is inherited through (paper section 6.2).
  std::string choicePrefix;
  std::vector<std::string> variations;  // in declaration order; "" if unnamed
  // Ordered as the choice file lists them: by variation, then by the
  // pipeline's world order.
  std::vector<Alternative> alternatives;
  bool isInput = false;
};

// A requirement of the pipeline: `component` must be available in `world`
// (the exported output in its world, vertexExport's position in Vertex).
struct Sink {
  sem::ComponentId component = 0;
  sem::WorldId world = 0;
};

class ShaderGraph {
 public:
  // Builds the graph, reporting components that cannot be defined anywhere,
  // explicit definitions whose dependencies are unavailable and required
  // components left undefined. Returns null after such errors.
  static std::unique_ptr<ShaderGraph> build(const sem::Shader& shader, DiagnosticList& diags);

  const sem::Shader& shader() const { return *shader_; }
  const sem::Pipeline& pipeline() const { return *shader_->pipeline; }
  const std::vector<ComponentNode>& nodes() const { return nodes_; }
  const ComponentNode& node(sem::ComponentId id) const { return nodes_[id]; }
  const std::vector<Sink>& sinks() const { return sinks_; }
  // Components with producers before consumers.
  const std::vector<sem::ComponentId>& dependencyOrder() const { return order_; }
  // Position of a component in dependencyOrder().
  uint32_t dependencyRank(sem::ComponentId c) const { return rank_[c]; }
  // Position of each world in the pipeline's topological order.
  uint32_t worldRank(sem::WorldId world) const { return worldRank_[world]; }
  bool reaches(sem::WorldId from, sem::WorldId to) const { return (reachable_[from] >> to) & 1; }
  // Worlds where `component`, computed or supplied in `world`, can be read:
  // those `world` reaches, except that an opaque value (a sampler) only
  // reaches the worlds that import it directly with a strategy that carries
  // opaque values (no export strategy can write one).
  WorldMask readableFrom(sem::ComponentId component, sem::WorldId world) const;
  // The imports that carry `component` from `from` to `to`: the pipeline's
  // route, or for an opaque value the direct import readableFrom() admits.
  std::vector<uint32_t> route(sem::ComponentId component, sem::WorldId from, sem::WorldId to) const;
  // Worlds where `component` can be read without its value coming from or
  // through a world in `locked`.
  WorldMask availableAvoiding(sem::ComponentId component, WorldMask locked) const;

  // "World" or "World:variation", as choice and decision files spell it.
  std::string altName(const ComponentNode& node, AltId alt) const;
  std::optional<AltId> findAlternative(const ComponentNode& node, std::string_view world,
                                       std::string_view variation) const;

 private:
  ShaderGraph() = default;
  bool expand(DiagnosticList& diags);
  // Fills order_ and rank_.
  void orderComponents();
  // Each expand step below returns false after reporting an error; `available`
  // holds, for each component placed so far, the worlds where it can be read.
  bool expandComponent(sem::ComponentId id, WorldMask concrete, std::vector<WorldMask>& available,
                       const std::vector<bool>& failed, DiagnosticList& diags);
  // The node's identity, choice prefix and variations.
  void describeNode(sem::ComponentId id);
  bool addExplicitAlternative(ComponentNode& node, const sem::Definition& d, const std::vector<WorldMask>& available,
                              DiagnosticList& diags);
  bool addImplicitAlternatives(ComponentNode& node, const sem::Definition& d, WorldMask concrete,
                               const std::vector<WorldMask>& available, DiagnosticList& diags);
  // Why an implicit definition with these candidate worlds fits in none.
  std::string explainNowhere(const sem::Component& component, const sem::Definition& d, WorldMask candidates,
                             const std::vector<WorldMask>& available) const;
  // Worlds where definition `d` may read `dep`.
  WorldMask readableBy(const sem::Definition& d, sem::ComponentId dep, const std::vector<WorldMask>& available) const;
  void collectSinks();
  // A component written by a shader that finalizes worlds, or above it, and
  // computable in one of them, is computed only in locked worlds, in every
  // shader derived from it: so no derived shader can pull it out of a
  // locked world (to read it earlier) and change the locked kernel.
  void keepInLockedWorlds(ComponentNode& node) const;

  const sem::Shader* shader_ = nullptr;
  std::vector<ComponentNode> nodes_;
  std::vector<Sink> sinks_;
  std::vector<sem::ComponentId> order_;
  std::vector<uint32_t> rank_;
  std::vector<uint32_t> worldRank_;
  std::vector<WorldMask> reachable_;
};

// Shaders for which variants are built: instances and shaders that no other
// shader derives from and no group lists.
std::vector<const sem::Shader*> concreteShaders(const sem::Model& model);

}  // namespace spire::graph

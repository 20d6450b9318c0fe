#include "graph/shader_graph.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <set>

#include "graph/locked_placement.h"

namespace spire::graph {
namespace {

std::string worldList(const sem::Pipeline& pipeline, WorldMask mask) {
  std::string text;
  for (sem::WorldId w : pipeline.topologicalOrder) {
    if (!((mask >> w) & 1) || pipeline.worlds[w].isAbstract) continue;
    text += fmt::format("{}{}", text.empty() ? "" : ", ", pipeline.worlds[w].name);
  }
  return text.empty() ? "no world that computes" : text;
}

// The worlds locked for `shader` at or below `origin`: those finalized by
// `origin` or by a shader between it and `shader`, where what `origin`
// wrote must stay when it can (keepInLockedWorlds).
WorldMask pinnedWorldsFor(const sem::Shader& shader, const std::string& origin) {
  WorldMask pinned = 0;
  for (const sem::Shader* s = &shader; s; s = s->base) {
    for (const ast::NameRef& ref : s->decl->finalizes) {
      if (auto w = shader.pipeline->findWorld(ref.name)) pinned |= WorldMask{1} << *w;
    }
    if (s->name == origin) return pinned;
  }
  return pinned;  // a pipeline component sits above every shader
}

// The position of `variation` in the node's variations.
uint32_t variationIndex(const ComponentNode& node, const std::string& variation) {
  return static_cast<uint32_t>(std::find(node.variations.begin(), node.variations.end(), variation) -
                               node.variations.begin());
}

// The import from `from` to `to` that carries opaque values, if any.
std::optional<uint32_t> opaqueImport(const sem::Pipeline& pipeline, sem::WorldId from, sem::WorldId to) {
  for (uint32_t k = 0; k < pipeline.imports.size(); ++k) {
    const sem::Import& i = pipeline.imports[k];
    if (i.from == from && i.to == to && i.strategy.signature && i.strategy.signature->carriesOpaque) return k;
  }
  return std::nullopt;
}

}  // namespace

WorldMask ShaderGraph::readableFrom(sem::ComponentId component, sem::WorldId world) const {
  if (!nodes_[component].component->type->containsOpaque()) return reachable_[world];
  WorldMask mask = WorldMask{1} << world;
  for (sem::WorldId to = 0; to < pipeline().worlds.size(); ++to) {
    if (opaqueImport(pipeline(), world, to)) mask |= WorldMask{1} << to;
  }
  return mask;
}

void ShaderGraph::keepInLockedWorlds(ComponentNode& node) const {
  WorldMask pinned = 0;
  for (const sem::Definition& d : node.component->definitions) pinned |= pinnedWorldsFor(*shader_, d.origin);
  auto outside = [&](const Alternative& a) { return !((pinned >> a.world) & 1); };
  if (std::all_of(node.alternatives.begin(), node.alternatives.end(), outside)) return;
  node.alternatives.erase(std::remove_if(node.alternatives.begin(), node.alternatives.end(), outside),
                          node.alternatives.end());
}

WorldMask ShaderGraph::availableAvoiding(sem::ComponentId component, WorldMask locked) const {
  WorldMask mask = 0;
  for (const Alternative& alt : nodes_[component].alternatives) {
    if ((locked >> alt.world) & 1) continue;
    const WorldMask readable = readableFrom(component, alt.world);
    for (sem::WorldId to = 0; to < pipeline().worlds.size(); ++to) {
      if (!((readable >> to) & 1)) continue;
      const std::vector<uint32_t> chain = route(component, alt.world, to);
      const bool crosses = std::any_of(chain.begin(), chain.end(), [&](uint32_t k) {
        const sem::WorldId via = pipeline().imports[k].to;
        return via != to && ((locked >> via) & 1);
      });
      if (!crosses) mask |= WorldMask{1} << to;
    }
  }
  return mask;
}

std::vector<uint32_t> ShaderGraph::route(sem::ComponentId component, sem::WorldId from, sem::WorldId to) const {
  if (nodes_[component].component->type->containsOpaque()) {
    if (const auto direct = opaqueImport(pipeline(), from, to)) return {*direct};
  }
  return pipeline().route(from, to);
}

std::vector<const sem::Shader*> concreteShaders(const sem::Model& model) {
  std::set<const sem::Shader*> abstractOnes;
  for (const auto& s : model.shaders) {
    if (s->base) abstractOnes.insert(s->base);
  }
  for (const auto& g : model.groups) {
    if (g->derivedDecl) continue;
    for (const sem::GroupMember& m : g->members) abstractOnes.insert(m.shader);
  }
  std::vector<const sem::Shader*> result;
  for (const auto& s : model.shaders) {
    if (s->valid && !abstractOnes.count(s.get())) result.push_back(s.get());
  }
  return result;
}

std::unique_ptr<ShaderGraph> ShaderGraph::build(const sem::Shader& shader, DiagnosticList& diags) {
  const sem::Pipeline& pipeline = *shader.pipeline;
  if (pipeline.worlds.size() > kMaxWorlds) {
    diags.reportOnce(DiagCode::E4016, pipeline.decl->nameRange,
                     fmt::format("pipeline '{}' has {} worlds; at most {} are supported", pipeline.name,
                                 pipeline.worlds.size(), kMaxWorlds));
    return nullptr;
  }
  if (!pipeline.valid || pipeline.topologicalOrder.size() != pipeline.worlds.size()) return nullptr;
  std::unique_ptr<ShaderGraph> graph(new ShaderGraph());
  graph->shader_ = &shader;
  const size_t worldCount = pipeline.worlds.size();
  graph->worldRank_.assign(worldCount, 0);
  for (uint32_t i = 0; i < worldCount; ++i) graph->worldRank_[pipeline.topologicalOrder[i]] = i;
  graph->reachable_.assign(worldCount, 0);
  for (sem::WorldId from = 0; from < worldCount; ++from) {
    for (sem::WorldId to = 0; to < worldCount; ++to) {
      if (pipeline.reaches(from, to)) graph->reachable_[from] |= WorldMask{1} << to;
    }
  }
  if (!graph->expand(diags)) return nullptr;
  return graph;
}

void ShaderGraph::orderComponents() {
  const sem::Shader& shader = *shader_;
  const size_t n = shader.components.size();
  // Producers before consumers (sema has rejected cycles).
  std::vector<uint8_t> state(n, 0);
  auto depsOf = [&](sem::ComponentId id) {
    std::vector<sem::ComponentId> deps;
    for (const sem::Definition& d : shader.components[id].definitions) {
      deps.insert(deps.end(), d.dependencies.begin(), d.dependencies.end());
    }
    return deps;
  };
  for (sem::ComponentId root = 0; root < n; ++root) {
    if (state[root]) continue;
    std::vector<std::pair<sem::ComponentId, std::vector<sem::ComponentId>>> stack;
    stack.emplace_back(root, depsOf(root));
    state[root] = 1;
    while (!stack.empty()) {
      auto& [id, pending] = stack.back();
      if (pending.empty()) {
        state[id] = 2;
        order_.push_back(id);
        stack.pop_back();
        continue;
      }
      const sem::ComponentId next = pending.back();
      pending.pop_back();
      if (state[next] == 0) {
        state[next] = 1;
        stack.emplace_back(next, depsOf(next));
      }
    }
  }
  rank_.assign(n, 0);
  for (uint32_t i = 0; i < order_.size(); ++i) rank_[order_[i]] = i;
}

bool ShaderGraph::expand(DiagnosticList& diags) {
  const sem::Pipeline& pipeline = *shader_->pipeline;
  const size_t n = shader_->components.size();
  orderComponents();
  nodes_.resize(n);
  std::vector<WorldMask> available(n, 0);
  std::vector<bool> failed(n, false);
  WorldMask concrete = 0;
  for (sem::WorldId w = 0; w < pipeline.worlds.size(); ++w) {
    if (!pipeline.worlds[w].isAbstract) concrete |= WorldMask{1} << w;
  }
  bool ok = true;
  for (sem::ComponentId id : order_) {
    if (expandComponent(id, concrete, available, failed, diags)) continue;
    ok = false;
    failed[id] = true;
  }
  collectSinks();
  return ok;
}

void ShaderGraph::describeNode(sem::ComponentId id) {
  const sem::Shader& shader = *shader_;
  const sem::Component& component = shader.components[id];
  ComponentNode& node = nodes_[id];
  node.id = id;
  node.component = &component;
  node.isInput = !component.definitions.empty() && component.definitions.front().isInput();
  const bool ownsDefinition = std::any_of(component.definitions.begin(), component.definitions.end(),
                                          [&](const sem::Definition& d) { return d.origin == shader.name; });
  node.choicePrefix = ownsDefinition || !shader.base ? shader.name : shader.base->name;
  for (const sem::Definition& d : component.definitions) {
    if (std::find(node.variations.begin(), node.variations.end(), d.variation) == node.variations.end()) {
      node.variations.push_back(d.variation);
    }
  }
}

bool ShaderGraph::expandComponent(sem::ComponentId id, WorldMask concrete, std::vector<WorldMask>& available,
                                  const std::vector<bool>& failed, DiagnosticList& diags) {
  const sem::Shader& shader = *shader_;
  const sem::Component& component = shader.components[id];
  describeNode(id);
  ComponentNode& node = nodes_[id];
  if (component.isAbstract && component.definitions.empty()) {
    diags
        .report(DiagCode::E4013, shader.decl->nameRange,
                fmt::format("shader '{}' does not define '{}', which '{}' requires", shader.name, component.name,
                            component.origin))
        .note(component.firstDecl->nameRange, fmt::format("'{}' is declared abstract here", component.name));
    return false;
  }
  const bool depFailed = std::any_of(component.definitions.begin(), component.definitions.end(), [&](const auto& d) {
    return std::any_of(d.dependencies.begin(), d.dependencies.end(), [&](sem::ComponentId dep) { return failed[dep]; });
  });
  if (depFailed) return false;

  bool ok = true;
  for (const sem::Definition& d : component.definitions) {
    const bool placed = d.world ? addExplicitAlternative(node, d, available, diags)
                                : addImplicitAlternatives(node, d, concrete, available, diags);
    ok = ok && placed;
  }
  keepInLockedWorlds(node);
  std::stable_sort(node.alternatives.begin(), node.alternatives.end(), [&](const Alternative& a, const Alternative& b) {
    if (a.variation != b.variation) return a.variation < b.variation;
    return worldRank_[a.world] < worldRank_[b.world];
  });
  for (const Alternative& alt : node.alternatives) available[id] |= readableFrom(id, alt.world);
  return ok;
}

WorldMask ShaderGraph::readableBy(const sem::Definition& d, sem::ComponentId dep,
                                  const std::vector<WorldMask>& available) const {
  // A definition written below a shader that finalizes worlds reads nothing
  // from or through them (section 6.2), or the locked kernels would depend on
  // the derived shader.
  const WorldMask locked = lockedAbove(*shader_, d.origin);
  return locked ? availableAvoiding(dep, locked) : available[dep];
}

bool ShaderGraph::addExplicitAlternative(ComponentNode& node, const sem::Definition& d,
                                         const std::vector<WorldMask>& available, DiagnosticList& diags) {
  const sem::Shader& shader = *shader_;
  const sem::Pipeline& pipeline = *shader.pipeline;
  bool ok = true;
  for (size_t i = 0; i < d.dependencies.size(); ++i) {
    const sem::ComponentId dep = d.dependencies[i];
    if ((readableBy(d, dep, available) >> *d.world) & 1) continue;
    const bool throughLocked = (available[dep] >> *d.world) & 1;
    diags.reportOnce(
        DiagCode::E4015, d.dependencyUses[i],
        fmt::format("'{}' is not available in world '{}', where '{}' is defined ({})", shader.components[dep].name,
                    pipeline.worlds[*d.world].name, node.component->name,
                    throughLocked ? fmt::format("it would come from or through a finalized world, "
                                                "and a derived shader reads nothing there")
                                  : fmt::format("it is available in {}", worldList(pipeline, available[dep]))));
    ok = false;
  }
  node.alternatives.push_back({*d.world, variationIndex(node, d.variation), &d});
  return ok;
}

bool ShaderGraph::addImplicitAlternatives(ComponentNode& node, const sem::Definition& d, WorldMask concrete,
                                          const std::vector<WorldMask>& available, DiagnosticList& diags) {
  // Implicit overloading (section 5.2): every concrete world where all
  // dependencies are available, except worlds an explicit definition of
  // the same variation already uses and worlds locked above the author.
  const sem::Component& component = *node.component;
  WorldMask candidates = concrete & ~lockedAbove(*shader_, d.origin);
  for (const sem::Definition& other : component.definitions) {
    if (other.world && other.variation == d.variation) candidates &= ~(WorldMask{1} << *other.world);
  }
  WorldMask allowed = candidates;
  for (sem::ComponentId dep : d.dependencies) allowed &= readableBy(d, dep, available);
  bool ok = true;
  if (allowed == 0 && component.definitions.size() == 1) {
    diags.reportOnce(DiagCode::E4014, d.decl->nameRange,
                     fmt::format("component '{}' can be defined nowhere: {}", component.name,
                                 explainNowhere(component, d, candidates, available)));
    ok = false;
  }
  for (sem::WorldId w = 0; w < pipeline().worlds.size(); ++w) {
    if ((allowed >> w) & 1) node.alternatives.push_back({w, variationIndex(node, d.variation), &d});
  }
  return ok;
}

std::string ShaderGraph::explainNowhere(const sem::Component& component, const sem::Definition& d, WorldMask candidates,
                                        const std::vector<WorldMask>& available) const {
  // Name the dependency that empties the set of possible worlds.
  WorldMask running = candidates;
  std::vector<std::string> seen;
  for (sem::ComponentId dep : d.dependencies) {
    const WorldMask readable = readableBy(d, dep, available);
    const WorldMask next = running & readable;
    seen.push_back(fmt::format("'{}' ({})", shader_->components[dep].name, worldList(pipeline(), readable)));
    if (next == 0) {
      return seen.size() == 1
                 ? fmt::format("it uses {}, which is available in no world where it could be computed", seen.front())
                 : fmt::format("no world has all of its dependencies; '{}' is blocked by {}", component.name,
                               fmt::join(seen, " and "));
    }
    running = next;
  }
  return "no world can compute it";
}

void ShaderGraph::collectSinks() {
  // Pipeline requirements: exports in their world, strategy arguments in the
  // world whose export strategy reads them.
  const sem::Shader& shader = *shader_;
  const sem::Pipeline& pipeline = *shader.pipeline;
  for (sem::ComponentId id = 0; id < shader.components.size(); ++id) {
    const sem::Component& c = shader.components[id];
    if (c.isExport && c.requiredWorld) sinks_.push_back({id, *c.requiredWorld});
  }
  for (sem::WorldId w = 0; w < pipeline.worlds.size(); ++w) {
    const auto& strategy = pipeline.worlds[w].exportStrategy;
    if (!strategy) continue;
    for (const std::string& name : strategy->componentArgs) {
      if (auto it = shader.componentByName.find(name); it != shader.componentByName.end()) {
        sinks_.push_back({it->second, w});
      }
    }
  }
}

std::string ShaderGraph::altName(const ComponentNode& node, AltId alt) const {
  const Alternative& a = node.alternatives[alt];
  const std::string& variation = node.variations[a.variation];
  const std::string& world = pipeline().worlds[a.world].name;
  return variation.empty() ? world : world + ":" + variation;
}

std::optional<AltId> ShaderGraph::findAlternative(const ComponentNode& node, std::string_view world,
                                                  std::string_view variation) const {
  for (AltId i = 0; i < node.alternatives.size(); ++i) {
    const Alternative& a = node.alternatives[i];
    if (pipeline().worlds[a.world].name == world && node.variations[a.variation] == variation) return i;
  }
  return std::nullopt;
}

}  // namespace spire::graph

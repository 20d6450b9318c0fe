#include "graph/variant_builder.h"

#include <algorithm>

namespace spire::graph {

VariantBuilder::VariantBuilder(const ShaderGraph& graph)
    : graph_(graph), levels_(lockLevels(graph.shader())), depth_(graph.nodes().size()) {
  if (levels_.empty()) return;
  for (const ComponentNode& node : graph.nodes()) {
    for (const Alternative& alt : node.alternatives) {
      depth_[node.id].push_back(lockDepth(graph.shader(), alt.definition->origin));
    }
  }
}

std::optional<Variant> VariantBuilder::place(const ChoiceSpace& domains, const Decided& decided) {
  const std::optional<std::vector<HeldLevel>> held = holdLevels(domains, decided);
  if (!held) return std::nullopt;
  std::optional<Placement> placement = searchHolding(domains, *held);
  if (!placement) return std::nullopt;
  return assemble(std::move(placement->choice));
}

std::optional<VariantBuilder::Placement> VariantBuilder::searchHolding(const ChoiceSpace& domains,
                                                                       const std::vector<HeldLevel>& held) const {
  std::optional<Placement> placement = search(domains, Rules{UINT32_MAX, &held});
  if (!placement) return std::nullopt;
  // The search checks what it places; a component the base passes to or
  // from a locked world must also stay placed (a derived decision can leave
  // it unread, and the locked kernel would lose it).
  for (const HeldLevel& level : held) {
    for (sem::ComponentId c = 0; c < graph_.nodes().size(); ++c) {
      if (level.footprints[c] && !level.footprints[c]->empty() && !placement->choice[c]) return std::nullopt;
    }
  }
  return placement;
}

std::optional<std::vector<VariantBuilder::HeldLevel>> VariantBuilder::holdLevels(const ChoiceSpace& domains,
                                                                                 const Decided& decided) const {
  std::vector<HeldLevel> held;
  for (uint32_t level = 0; level < levels_.size(); ++level) {
    std::optional<Placement> base = search(domains, Rules{level, &held, &decided});
    if (!base) return std::nullopt;
    held.push_back(holdLevel(std::move(*base), level));
  }
  return held;
}

bool VariantBuilder::owns(sem::ComponentId c, uint32_t level) const {
  const sem::Component& component = *graph_.node(c).component;
  if (component.requiredWorld && lockDepth(graph_.shader(), component.origin) <= level) return true;
  return std::any_of(depth_[c].begin(), depth_[c].end(), [&](uint32_t d) { return d <= level; });
}

VariantBuilder::HeldLevel VariantBuilder::holdLevel(Placement placement, uint32_t level) const {
  HeldLevel held{levels_[level].locked, std::move(placement), {}};
  held.footprints.resize(graph_.nodes().size());
  for (sem::ComponentId c = 0; c < graph_.nodes().size(); ++c) {
    if (!owns(c, level)) continue;
    // What the base does not compute, no derived read may bring into or
    // through a locked world either.
    const std::optional<AltId>& alt = held.placement.choice[c];
    held.footprints[c] =
        alt ? lockedFootprint(graph_, c, *alt, held.placement.reach[c], held.locked) : LockedFootprint{};
  }
  return held;
}

std::optional<VariantBuilder::Placement> VariantBuilder::search(const ChoiceSpace& domains, const Rules& rules) const {
  const size_t n = graph_.nodes().size();
  const auto& dependencyOrder = graph_.dependencyOrder();
  const std::vector<sem::ComponentId> order(dependencyOrder.rbegin(), dependencyOrder.rend());
  // Worlds each component must reach: its live consumers' and sinks'.
  std::vector<WorldMask> mustReach(n, 0);
  for (const Sink& sink : graph_.sinks()) mustReach[sink.component] |= WorldMask{1} << sink.world;

  std::vector<Frame> frames(order.size());
  Choice choice(n);
  size_t i = 0;
  size_t steps = 0;
  constexpr size_t kMaxSteps = 1'000'000;
  bool entering = true;
  while (i < order.size()) {
    if (++steps > kMaxSteps) return std::nullopt;
    const sem::ComponentId c = order[i];
    Frame& frame = frames[i];
    if (entering) {
      frame = Frame{};
      if (mustReach[c] == 0) {
        frame.skipped = true;  // not live
        ++i;
        continue;
      }
      frame.candidates = preferred(candidates(domains, c, rules), c);
    } else {
      // Backtracking into this frame: undo its choice.
      for (const auto& [dep, mask] : frame.saved) mustReach[dep] = mask;
      frame.saved.clear();
      choice[c].reset();
    }
    if (const std::optional<AltId> a = chooseNext(frame, c, domains, mustReach, rules)) {
      choice[c] = *a;
      ++i;
      entering = true;
      continue;
    }
    // Exhausted: return to the closest earlier frame that made a choice.
    do {
      if (i == 0) return std::nullopt;
      --i;
    } while (frames[i].skipped);
    entering = false;
  }
  return Placement{std::move(choice), std::move(mustReach)};
}

// Default preference per component: latest world, then first variation.
std::vector<AltId> VariantBuilder::candidates(const ChoiceSpace& domains, sem::ComponentId c,
                                              const Rules& rules) const {
  if (!rules.decided) return domains.aliveAlternatives(c);
  const std::optional<Decision>& decision = (*rules.decided)[c];
  if (decision && decision->lockDepth <= rules.counted) return {decision->alternative};
  // The base's own definitions where it has any: a derived shader's
  // redefinition must then deliver the value as they do.
  std::vector<AltId> all, own;
  for (AltId a = 0; a < graph_.node(c).alternatives.size(); ++a) {
    all.push_back(a);
    if (depth_[c][a] <= rules.counted) own.push_back(a);
  }
  return own.empty() ? all : own;
}

std::vector<AltId> VariantBuilder::preferred(std::vector<AltId> alts, sem::ComponentId c) const {
  const auto& all = graph_.node(c).alternatives;
  std::stable_sort(alts.begin(), alts.end(), [&](AltId a, AltId b) {
    const uint32_t ra = graph_.worldRank(all[a].world), rb = graph_.worldRank(all[b].world);
    if (ra != rb) return ra > rb;
    return all[a].variation < all[b].variation;
  });
  return alts;
}

bool VariantBuilder::fits(sem::ComponentId c, AltId a, const std::vector<WorldMask>& mustReach) const {
  const WorldMask reach = graph_.readableFrom(c, graph_.node(c).alternatives[a].world);
  return (reach & mustReach[c]) == mustReach[c];
}

bool VariantBuilder::keepsFootprints(sem::ComponentId c, AltId a, WorldMask reach, const Rules& rules) const {
  if (!rules.held) return true;
  return std::all_of(rules.held->begin(), rules.held->end(), [&](const HeldLevel& level) {
    const LockedFootprint footprint = lockedFootprint(graph_, c, a, reach, level.locked);
    if (level.footprints[c]) return footprint == *level.footprints[c];
    // A component only derived shaders define may reach a locked world,
    // never pass through one (paper section 6.2).
    return std::none_of(footprint.imports.begin(), footprint.imports.end(),
                        [&](uint32_t k) { return (level.locked >> graph_.pipeline().imports[k].from) & 1; });
  });
}

std::optional<AltId> VariantBuilder::chooseNext(Frame& frame, sem::ComponentId c, const ChoiceSpace& domains,
                                                std::vector<WorldMask>& mustReach, const Rules& rules) const {
  while (frame.next < frame.candidates.size()) {
    const AltId a = frame.candidates[frame.next++];
    // Consumers come first, so mustReach[c] is complete here.
    if (!fits(c, a, mustReach) || !keepsFootprints(c, a, mustReach[c], rules)) continue;
    if (!depth_[c].empty() && depth_[c][a] > rules.counted) return a;  // its reads do not count at this level
    const Alternative& alt = graph_.node(c).alternatives[a];
    bool supported = true;
    for (sem::ComponentId dep : alt.definition->dependencies) {
      frame.saved.emplace_back(dep, mustReach[dep]);
      mustReach[dep] |= WorldMask{1} << alt.world;
      bool any = false;
      for (AltId d : candidates(domains, dep, rules)) any = any || fits(dep, d, mustReach);
      supported = supported && any;
    }
    if (supported) return a;
    for (const auto& [dep, mask] : frame.saved) mustReach[dep] = mask;
    frame.saved.clear();
  }
  return std::nullopt;
}

std::optional<LockedMove> VariantBuilder::explainLockedMove(const ChoiceSpace& domains) const {
  const std::optional<std::vector<HeldLevel>> held = holdLevels(domains, Decided(graph_.nodes().size()));
  if (!held || held->empty() || searchHolding(domains, *held)) return std::nullopt;
  const std::optional<Placement> free = search(domains, Rules{});
  if (!free) return std::nullopt;
  for (uint32_t level = 0; level < held->size(); ++level) {
    for (sem::ComponentId c = 0; c < graph_.nodes().size(); ++c) {
      if (const auto move = movedBy(c, level, (*held)[level], *free)) return move;
      if (const auto move = passesThrough(c, level, (*held)[level], *free)) return move;
    }
  }
  return std::nullopt;
}

std::optional<LockedMove> VariantBuilder::passesThrough(sem::ComponentId c, uint32_t level, const HeldLevel& held,
                                                        const Placement& free) const {
  const std::optional<AltId>& alt = free.choice[c];
  if (held.footprints[c] || !alt) return std::nullopt;
  const sem::Pipeline& pipeline = graph_.pipeline();
  const sem::WorldId world = graph_.node(c).alternatives[*alt].world;
  for (const Read& read : readsOf(c, free)) {
    for (uint32_t k : graph_.route(c, world, read.world)) {
      const sem::WorldId from = pipeline.imports[k].from;
      if (!((held.locked >> from) & 1)) continue;
      return LockedMove{
          LockedMove::Kind::PassesThrough, c,   std::nullopt, *alt, read.reader, read.definition, read.use, read.world,
          levels_[level].finalizer,        from};
    }
  }
  return std::nullopt;
}

std::optional<LockedMove> VariantBuilder::movedBy(sem::ComponentId c, uint32_t level, const HeldLevel& held,
                                                  const Placement& free) const {
  const std::optional<AltId>& moved = free.choice[c];
  if (!held.footprints[c] || !moved) return std::nullopt;
  const LockedFootprint footprint = lockedFootprint(graph_, c, *moved, free.reach[c], held.locked);
  if (footprint == *held.footprints[c]) return std::nullopt;
  const std::optional<AltId>& base = held.placement.choice[c];
  for (const Read& read : readsOf(c, free)) {
    if (depth_[read.reader][*free.choice[read.reader]] <= level) continue;
    if (base && ((graph_.readableFrom(c, graph_.node(c).alternatives[*base].world) >> read.world) & 1)) continue;
    return LockedMove{LockedMove::Kind::Moved,
                      c,
                      base,
                      *moved,
                      read.reader,
                      read.definition,
                      read.use,
                      read.world,
                      levels_[level].finalizer,
                      changedLockedWorld(graph_, c, *held.footprints[c], footprint, held.locked)};
  }
  return std::nullopt;
}

std::vector<VariantBuilder::Read> VariantBuilder::readsOf(sem::ComponentId c, const Placement& placement) const {
  std::vector<Read> reads;
  for (sem::ComponentId r = 0; r < graph_.nodes().size(); ++r) {
    if (!placement.choice[r]) continue;
    const Alternative& reader = graph_.node(r).alternatives[*placement.choice[r]];
    const auto& deps = reader.definition->dependencies;
    const auto it = std::find(deps.begin(), deps.end(), c);
    if (it != deps.end()) reads.push_back({r, reader.definition, static_cast<size_t>(it - deps.begin()), reader.world});
  }
  return reads;
}

std::optional<Variant> VariantBuilder::assemble(Choice choice) {
  Variant v;
  v.graph_ = &graph_;
  v.choice_ = std::move(choice);
  v.worlds_.resize(graph_.pipeline().worlds.size());
  for (sem::ComponentId c : graph_.dependencyOrder()) {
    if (!v.choice_[c]) continue;
    v.live_.push_back(c);
    if (!graph_.node(c).isInput) v.worlds_[v.worldOf(c)].computed.push_back(c);
  }
  std::set<std::pair<sem::ComponentId, uint32_t>> seen;
  for (sem::ComponentId c : v.live_) {
    const Alternative& alt = graph_.node(c).alternatives[*v.choice_[c]];
    for (sem::ComponentId dep : alt.definition->dependencies) route(v, dep, v.worldOf(dep), alt.world, seen);
  }
  for (const Sink& sink : graph_.sinks()) route(v, sink.component, v.worldOf(sink.component), sink.world, seen);
  if (!routeStrategyArguments(v, seen)) return std::nullopt;
  return v;
}

// An import whose strategy takes arguments (`textureImport(vert_uv)`)
// evaluates them in the consuming world, so every import the variant uses
// brings its arguments there too; routing them may use further imports.
bool VariantBuilder::routeStrategyArguments(Variant& v, std::set<std::pair<sem::ComponentId, uint32_t>>& seen) {
  const auto& imports = graph_.pipeline().imports;
  std::set<uint32_t> handled;
  bool progress = true;
  while (progress) {
    progress = false;
    for (uint32_t k = 0; k < imports.size(); ++k) {
      const bool used = std::any_of(seen.begin(), seen.end(), [&](const auto& s) { return s.second == k; });
      if (!used || !handled.insert(k).second) continue;
      progress = true;
      for (const std::string& name : imports[k].strategy.componentArgs) {
        const sem::ComponentId arg = graph_.shader().componentByName.at(name);
        if (!v.choice_[arg]) {
          // Inputs have a single placement; a computed argument would need
          // its own placement decision, which pipelines do not use.
          if (!graph_.node(arg).isInput) return false;
          v.choice_[arg] = 0;
          v.live_.insert(std::upper_bound(v.live_.begin(), v.live_.end(), arg,
                                          [&](sem::ComponentId a, sem::ComponentId b) {
                                            return graph_.dependencyRank(a) < graph_.dependencyRank(b);
                                          }),
                         arg);
        }
        route(v, arg, v.worldOf(arg), imports[k].to, seen);
      }
    }
  }
  return true;
}

void VariantBuilder::route(Variant& v, sem::ComponentId component, sem::WorldId from, sem::WorldId to,
                           std::set<std::pair<sem::ComponentId, uint32_t>>& seen) {
  if (from == to) return;
  for (uint32_t importIndex : graph_.route(component, from, to)) {
    if (!seen.insert({component, importIndex}).second) continue;
    const sem::Import& import = graph_.pipeline().imports[importIndex];
    v.worlds_[import.from].outputs.push_back({component, importIndex});
    v.worlds_[import.to].inputs.push_back({component, importIndex});
  }
}

std::optional<LockedMove> explainLockedMove(const ChoiceSpace& space) {
  return VariantBuilder(space.graph()).explainLockedMove(space);
}

}  // namespace spire::graph

#include "graph/variant.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "graph/decision_file.h"
#include "sema/route_selection.h"

namespace spire::graph {

class VariantBuilder {
 public:
  explicit VariantBuilder(const ShaderGraph& graph) : graph_(graph) {}

  // Chooses an alternative for every live component, consumers first, with
  // backtracking when a choice leaves a dependency nowhere to go.
  std::optional<Variant> place(const ChoiceSpace& domains);

 private:
  // One component's step in the search: its candidates in preference order,
  // the next to try, and what its choice changed.
  struct Frame {
    std::vector<AltId> candidates;
    size_t next = 0;
    std::vector<std::pair<sem::ComponentId, WorldMask>> saved;  // mustReach before this choice
    bool skipped = false;
  };
  using Choice = std::vector<std::optional<AltId>>;

  // The backtracking search; nullopt when no placement exists or the search
  // gives up.
  std::optional<Choice> search(const ChoiceSpace& domains) const;
  std::vector<AltId> preferred(const ChoiceSpace& domains, sem::ComponentId c) const;
  // Whether alternative `a` of `c` reaches every world `c` must reach.
  bool fits(sem::ComponentId c, AltId a, const std::vector<WorldMask>& mustReach) const;
  // The frame's next candidate that fits and leaves each of its dependencies
  // an alternative that fits, with `mustReach` widened for it.
  std::optional<AltId> chooseNext(Frame& frame, sem::ComponentId c, const ChoiceSpace& domains,
                                  std::vector<WorldMask>& mustReach) const;
  // The variant of a complete choice: its live components, kernels and routes.
  std::optional<Variant> assemble(Choice choice);
  void route(Variant& v, sem::ComponentId component, sem::WorldId from, sem::WorldId to,
             std::set<std::pair<sem::ComponentId, uint32_t>>& seen);
  bool routeStrategyArguments(Variant& v, std::set<std::pair<sem::ComponentId, uint32_t>>& seen);

  const ShaderGraph& graph_;
};

std::optional<Variant> VariantBuilder::place(const ChoiceSpace& domains) {
  std::optional<Choice> choice = search(domains);
  if (!choice) return std::nullopt;
  return assemble(std::move(*choice));
}

std::optional<VariantBuilder::Choice> VariantBuilder::search(const ChoiceSpace& domains) const {
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
      frame.candidates = preferred(domains, c);
    } else {
      // Backtracking into this frame: undo its choice.
      for (const auto& [dep, mask] : frame.saved) mustReach[dep] = mask;
      frame.saved.clear();
      choice[c].reset();
    }
    if (const std::optional<AltId> a = chooseNext(frame, c, domains, mustReach)) {
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
  return choice;
}

// Default preference per component: latest world, then first variation.
std::vector<AltId> VariantBuilder::preferred(const ChoiceSpace& domains, sem::ComponentId c) const {
  std::vector<AltId> alts = domains.aliveAlternatives(c);
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

std::optional<AltId> VariantBuilder::chooseNext(Frame& frame, sem::ComponentId c, const ChoiceSpace& domains,
                                                std::vector<WorldMask>& mustReach) const {
  while (frame.next < frame.candidates.size()) {
    const AltId a = frame.candidates[frame.next++];
    if (!fits(c, a, mustReach)) continue;
    const Alternative& alt = graph_.node(c).alternatives[a];
    bool supported = true;
    for (sem::ComponentId dep : alt.definition->dependencies) {
      frame.saved.emplace_back(dep, mustReach[dep]);
      mustReach[dep] |= WorldMask{1} << alt.world;
      bool any = false;
      for (AltId d : domains.aliveAlternatives(dep)) any = any || fits(dep, d, mustReach);
      supported = supported && any;
    }
    if (supported) return a;
    for (const auto& [dep, mask] : frame.saved) mustReach[dep] = mask;
    frame.saved.clear();
  }
  return std::nullopt;
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

const std::vector<std::pair<std::string, std::string>>& Variant::attributes(sem::ComponentId c) const {
  static const std::vector<std::pair<std::string, std::string>> kNone;
  auto it = attributes_.find(c);
  return it == attributes_.end() ? kNone : it->second;
}

std::string Variant::placementText() const {
  std::string out;
  for (sem::ComponentId c : live_) {
    const ComponentNode& node = graph_->node(c);
    if (node.isInput) continue;
    out += writeDecisionLine(makeDecision(node.choicePrefix, node.component->name, graph_->altName(node, *choice_[c])));
  }
  return out;
}

std::string Variant::describe() const {
  std::string out = placementText();
  const sem::Pipeline& pipeline = graph_->pipeline();
  auto names = [&](const std::vector<sem::ComponentId>& ids) {
    std::string text;
    for (sem::ComponentId c : ids)
      text += fmt::format("{}{}", text.empty() ? "" : ", ", graph_->node(c).component->name);
    return text;
  };
  auto transfers = [&](const std::vector<Transfer>& list, bool incoming) {
    std::string text;
    for (const Transfer& t : list) {
      const sem::Import& import = pipeline.imports[t.importIndex];
      text += fmt::format("{}{} {} {} ({})", text.empty() ? "" : ", ", graph_->node(t.component).component->name,
                          incoming ? "from" : "to", pipeline.worlds[incoming ? import.from : import.to].name,
                          import.strategy.ref->name);
    }
    return text;
  };
  for (sem::WorldId w : pipeline.topologicalOrder) {
    const WorldPlan& plan = worlds_[w];
    if (plan.computed.empty() && plan.inputs.empty() && plan.outputs.empty()) continue;
    out += fmt::format("// world {}\n", pipeline.worlds[w].name);
    if (!plan.computed.empty()) out += fmt::format("//   computes: {}\n", names(plan.computed));
    if (!plan.inputs.empty()) out += fmt::format("//   imports:  {}\n", transfers(plan.inputs, true));
    if (!plan.outputs.empty()) out += fmt::format("//   exports:  {}\n", transfers(plan.outputs, false));
  }
  return out + describeRoutes();
}

std::string Variant::describeRoutes() const {
  const sem::Pipeline& pipeline = graph_->pipeline();
  std::string out;
  for (sem::ComponentId c : live_) {
    // The worlds the value reaches and does not pass on: each one's route
    // shows every world the value crosses on the way.
    std::set<sem::WorldId> reached, forwarding;
    for (const WorldPlan& plan : worlds_) {
      for (const Transfer& t : plan.inputs) {
        if (t.component != c) continue;
        reached.insert(pipeline.imports[t.importIndex].to);
        forwarding.insert(pipeline.imports[t.importIndex].from);
      }
    }
    std::string routes;
    for (sem::WorldId w : reached) {
      if (forwarding.count(w)) continue;
      std::string chain = pipeline.worlds[worldOf(c)].name, steps;
      for (uint32_t k : graph_->route(c, worldOf(c), w)) {
        const sem::Import& import = pipeline.imports[k];
        chain += " -> " + pipeline.worlds[import.to].name;
        steps += fmt::format("{}{} {}", steps.empty() ? "" : ", ", import.strategy.ref->name,
                             sem::transferName(sem::transferOf(pipeline, import)));
      }
      routes += fmt::format("{}{} ({})", routes.empty() ? "" : "; ", chain, steps);
    }
    if (!routes.empty()) out += fmt::format("//   {}: {}\n", graph_->node(c).component->name, routes);
  }
  return out.empty() ? out : "// routes\n" + out;
}

VariantResult buildVariant(const ChoiceSpace& space, const std::vector<DecisionRequest>& requests) {
  VariantResult result;
  result.outcomes.resize(requests.size());
  ChoiceSpace current = space;
  std::vector<size_t> applied;
  for (size_t r = 0; r < requests.size(); ++r) {
    const DecisionRequest& request = requests[r];
    DecisionOutcome& outcome = result.outcomes[r];
    if (!space.alive(request.component, request.alternative)) {
      outcome.status = DecisionStatus::NotAChoice;
      continue;
    }
    ChoiceSpace trial = current;
    if (trial.restrict(request.component, request.alternative)) {
      current = std::move(trial);
      applied.push_back(r);
      continue;
    }
    // Name the earliest decision that, with this one, has no variant.
    outcome.status = DecisionStatus::Conflict;
    outcome.conflictsWith = applied.empty() ? r : applied.back();
    ChoiceSpace prefix = space;
    for (size_t index : applied) {
      prefix.restrict(requests[index].component, requests[index].alternative);
      ChoiceSpace probe = prefix;
      if (!probe.restrict(request.component, request.alternative)) {
        outcome.conflictsWith = index;
        break;
      }
    }
  }
  VariantBuilder builder(space.graph());
  result.variant = builder.place(current);
  // Propagation is not complete search; if placement still fails, drop the
  // latest decisions until it succeeds.
  while (!result.variant && !applied.empty()) {
    const size_t dropped = applied.back();
    applied.pop_back();
    result.outcomes[dropped] = {DecisionStatus::Conflict, applied.empty() ? dropped : applied.back()};
    current = space;
    for (size_t index : applied) current.restrict(requests[index].component, requests[index].alternative);
    result.variant = builder.place(current);
  }
  if (result.variant) {
    for (size_t index : applied) {
      if (!requests[index].attributes.empty()) {
        auto& list = result.variant->attributes_[requests[index].component];
        list.insert(list.end(), requests[index].attributes.begin(), requests[index].attributes.end());
      }
    }
  }
  return result;
}

}  // namespace spire::graph

#include "graph/variant.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "graph/decision_file.h"
#include "graph/variant_builder.h"
#include "sema/route_selection.h"

namespace spire::graph {

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

namespace {

// The variant of the space under the applied requests. Propagation is not
// complete search, so when placement fails the latest applied decisions
// are dropped until it succeeds; then each dropped one but the last (whose
// removal let it succeed) is taken back, in order, if it still places.
std::optional<Variant> placeApplied(const ChoiceSpace& space, const std::vector<DecisionRequest>& requests,
                                    std::vector<size_t>& applied, std::vector<DecisionOutcome>& outcomes) {
  VariantBuilder builder(space.graph());
  const auto placeWith = [&](const std::vector<size_t>& indices) -> std::optional<Variant> {
    ChoiceSpace current = space;
    VariantBuilder::Decided decided(space.graph().nodes().size());
    for (size_t index : indices) {
      if (!current.restrict(requests[index].component, requests[index].alternative)) return std::nullopt;
      decided[requests[index].component] =
          VariantBuilder::Decision{requests[index].alternative, requests[index].lockDepth};
    }
    return builder.place(current, decided);
  };
  std::optional<Variant> variant = placeWith(applied);
  std::vector<size_t> dropped;
  while (!variant && !applied.empty()) {
    dropped.push_back(applied.back());
    applied.pop_back();
    outcomes[dropped.back()] = {DecisionStatus::Conflict, applied.empty() ? dropped.back() : applied.back()};
    variant = placeWith(applied);
  }
  if (!variant || dropped.size() < 2) return variant;
  for (auto it = dropped.rbegin() + 1; it != dropped.rend(); ++it) {
    std::vector<size_t> trial = applied;
    trial.push_back(*it);
    if (std::optional<Variant> retaken = placeWith(trial)) {
      applied = std::move(trial);
      outcomes[*it] = {};
      variant = std::move(retaken);
    }
  }
  return variant;
}

}  // namespace

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
  result.variant = placeApplied(space, requests, applied, result.outcomes);
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

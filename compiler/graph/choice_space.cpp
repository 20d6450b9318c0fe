#include "graph/choice_space.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>

namespace spire::graph {
namespace {

bool dependsOn(const Alternative& alt, sem::ComponentId dep) {
  const auto& deps = alt.definition->dependencies;
  return std::binary_search(deps.begin(), deps.end(), dep);
}

}  // namespace

ChoiceSpace::ChoiceSpace(const ShaderGraph& graph) : graph_(&graph) {
  const size_t n = graph.nodes().size();
  alive_.resize(n);
  for (sem::ComponentId c = 0; c < n; ++c) alive_[c].assign(graph.node(c).alternatives.size(), 1);
  available_.assign(n, 0);
  mandatory_.assign(n, false);
  for (sem::ComponentId c = 0; c < n; ++c) available_[c] = worldsOf(c);
  consistent_ = propagate();
}

WorldMask ChoiceSpace::worldsOf(sem::ComponentId c) const {
  WorldMask mask = 0;
  const auto& alts = graph_->node(c).alternatives;
  for (AltId a = 0; a < alts.size(); ++a) {
    if (alive_[c][a]) mask |= graph_->readableFrom(c, alts[a].world);
  }
  return mask;
}

std::vector<AltId> ChoiceSpace::aliveAlternatives(sem::ComponentId c) const {
  std::vector<AltId> result;
  for (AltId a = 0; a < alive_[c].size(); ++a) {
    if (alive_[c][a]) result.push_back(a);
  }
  return result;
}

uint32_t ChoiceSpace::aliveCount(sem::ComponentId c) const {
  return static_cast<uint32_t>(std::count(alive_[c].begin(), alive_[c].end(), 1));
}

void ChoiceSpace::kill(sem::ComponentId c, AltId a, bool& changed) {
  if (!alive_[c][a]) return;
  alive_[c][a] = 0;
  changed = true;
}

bool ChoiceSpace::restrict(sem::ComponentId c, AltId alt) {
  for (AltId a = 0; a < alive_[c].size(); ++a) {
    if (a != alt) alive_[c][a] = 0;
  }
  // The decided component must keep its alternative even when nothing
  // requires it to be live: otherwise the decision could never take effect.
  consistent_ = consistent_ && alive_[c][alt] && propagate() && alive_[c][alt];
  return consistent_;
}

bool ChoiceSpace::forwardPass() {
  bool changed = false;
  // Producers first, so one pass settles most chains.
  for (sem::ComponentId c : graph_->dependencyOrder()) {
    const auto& alts = graph_->node(c).alternatives;
    bool killed = false;
    for (AltId a = 0; a < alts.size(); ++a) {
      if (!alive_[c][a]) continue;
      for (sem::ComponentId dep : alts[a].definition->dependencies) {
        if (!((available_[dep] >> alts[a].world) & 1)) {
          kill(c, a, killed);
          break;
        }
      }
    }
    if (killed) {
      available_[c] = worldsOf(c);
      changed = true;
    }
  }
  return changed;
}

bool ChoiceSpace::backwardPass() {
  bool changed = false;
  const auto& order = graph_->dependencyOrder();
  std::fill(mandatory_.begin(), mandatory_.end(), false);
  std::vector<std::vector<WorldMask>> requirements(graph_->nodes().size());
  for (const Sink& sink : graph_->sinks()) {
    mandatory_[sink.component] = true;
    requirements[sink.component].push_back(WorldMask{1} << sink.world);
  }
  // Consumers first: a mandatory component makes mandatory whatever all of
  // its remaining alternatives read, and constrains where that may live.
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const sem::ComponentId c = *it;
    if (!mandatory_[c]) continue;
    const auto& alts = graph_->node(c).alternatives;
    for (const WorldMask required : requirements[c]) {
      bool killed = false;
      for (AltId a = 0; a < alts.size(); ++a) {
        if (alive_[c][a] && !(graph_->readableFrom(c, alts[a].world) & required)) kill(c, a, killed);
      }
      if (killed) {
        available_[c] = worldsOf(c);
        changed = true;
      }
    }
    WorldMask worlds = 0;
    std::vector<AltId> remaining;
    for (AltId a = 0; a < alts.size(); ++a) {
      if (!alive_[c][a]) continue;
      remaining.push_back(a);
      worlds |= WorldMask{1} << alts[a].world;
    }
    if (remaining.empty()) continue;
    for (sem::ComponentId dep : alts[remaining.front()].definition->dependencies) {
      const bool always =
          std::all_of(remaining.begin(), remaining.end(), [&](AltId a) { return dependsOn(alts[a], dep); });
      if (!always) continue;
      mandatory_[dep] = true;
      requirements[dep].push_back(worlds);
    }
  }
  return changed;
}

bool ChoiceSpace::propagate() {
  bool changed = true;
  while (changed) {
    changed = forwardPass();
    changed = backwardPass() || changed;
  }
  for (sem::ComponentId c = 0; c < alive_.size(); ++c) {
    if (mandatory_[c] && aliveCount(c) == 0) return false;
  }
  return true;
}

std::vector<bool> ChoiceSpace::possiblyLive() const {
  std::vector<bool> seen(alive_.size(), false);
  std::vector<sem::ComponentId> work;
  for (const Sink& sink : graph_->sinks()) {
    if (!seen[sink.component]) {
      seen[sink.component] = true;
      work.push_back(sink.component);
    }
  }
  while (!work.empty()) {
    const sem::ComponentId c = work.back();
    work.pop_back();
    const auto& alts = graph_->node(c).alternatives;
    for (AltId a = 0; a < alts.size(); ++a) {
      if (!alive_[c][a]) continue;
      for (sem::ComponentId dep : alts[a].definition->dependencies) {
        if (!seen[dep]) {
          seen[dep] = true;
          work.push_back(dep);
        }
      }
    }
  }
  return seen;
}

namespace {

// Every possibly-live computed component with its remaining alternatives,
// in declaration order; choices are those with more than one.
std::vector<Choice> placements(const ChoiceSpace& space) {
  const ShaderGraph& graph = space.graph();
  const std::vector<bool> live = space.possiblyLive();
  std::vector<Choice> result;
  for (const ComponentNode& node : graph.nodes()) {
    if (node.isInput || !live[node.id] || space.aliveCount(node.id) == 0) continue;
    Choice choice{node.id, fmt::format("{}.{}", node.choicePrefix, node.component->name), {}, {}};
    for (AltId a : space.aliveAlternatives(node.id)) {
      choice.alternatives.push_back(a);
      choice.names.push_back(graph.altName(node, a));
    }
    result.push_back(std::move(choice));
  }
  return result;
}

// One key of the choice file over several shaders: the alternatives each
// shader that has the component live allows.
struct SharedKey {
  std::string key;
  bool isChoice = false;  // more than one alternative in some shader
  std::vector<std::pair<std::string, std::vector<std::string>>> shaders;
};

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// The line lists what every shader allows (in the first shader's order), so
// that a decision with this key is valid for all of them; an alternative only
// some allow gets a comment line naming them.
std::string writeSharedKey(const SharedKey& k) {
  std::vector<std::string> all;  // every alternative, in order of appearance
  for (const auto& [shader, names] : k.shaders) {
    for (const std::string& name : names) {
      if (!contains(all, name)) all.push_back(name);
    }
  }
  std::string comments;
  std::vector<std::string> common;
  for (const std::string& name : all) {
    std::vector<std::string> allowing;
    for (const auto& [shader, names] : k.shaders) {
      if (contains(names, name)) allowing.push_back(shader);
    }
    if (allowing.size() == k.shaders.size())
      common.push_back(name);
    else
      comments += fmt::format("// {} is possible only for {}\n", name, fmt::join(allowing, ", "));
  }
  if (common.empty()) return comments;
  return fmt::format("{}{} = {{{}}}\n", comments, k.key, fmt::join(common, ","));
}

}  // namespace

std::vector<Choice> enumerateChoices(const ChoiceSpace& space) {
  std::vector<Choice> choices = placements(space);
  std::erase_if(choices, [](const Choice& c) { return c.alternatives.size() < 2; });
  return choices;
}

std::string writeChoiceFile(const ChoiceSpace& space) { return writeChoiceFile(std::vector{&space}); }

std::string writeChoiceFile(const std::vector<const ChoiceSpace*>& spaces) {
  std::vector<SharedKey> keys;
  std::map<std::string, size_t, std::less<>> index;
  for (const ChoiceSpace* space : spaces) {
    for (Choice& p : placements(*space)) {
      const auto [it, added] = index.try_emplace(p.key, keys.size());
      if (added) keys.push_back({p.key, false, {}});
      SharedKey& k = keys[it->second];
      k.isChoice = k.isChoice || p.names.size() > 1;
      k.shaders.emplace_back(space->graph().shader().name, std::move(p.names));
    }
  }
  std::string out;
  for (const SharedKey& k : keys) {
    if (k.isChoice) out += writeSharedKey(k);
  }
  return out;
}

}  // namespace spire::graph

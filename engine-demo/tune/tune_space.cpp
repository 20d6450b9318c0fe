#include "tune/tune_space.h"

#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <set>

#include "graph/shader_graph.h"

namespace spire::tune {

namespace {

// "Terrain.albedo" -> "albedo".
std::string componentOf(const std::string& key) {
  const size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

bool kept(const std::string& placement, const std::vector<std::string>& only) {
  if (only.empty()) return true;
  const size_t colon = placement.find(':');
  const std::string world = placement.substr(0, colon);
  const std::string variation = colon == std::string::npos ? "" : placement.substr(colon + 1);
  return std::any_of(only.begin(), only.end(), [&](const std::string& name) {
    return name == world || (!variation.empty() && name == variation);
  });
}

}  // namespace

std::map<std::string, std::set<std::string>> transitionPlacements(const graph::ChoiceSpace& space) {
  std::map<std::string, std::set<std::string>> placements;
  const graph::ShaderGraph& graph = space.graph();
  for (const graph::Choice& choice : graph::enumerateChoices(space)) {
    const graph::ComponentNode& node = graph.node(choice.component);
    for (size_t i = 0; i < choice.alternatives.size() && i < choice.names.size(); ++i) {
      const sem::Definition* definition = node.alternatives.at(choice.alternatives[i]).definition;
      if (definition && definition->decl && ast::hasAttribute(definition->decl->attributes, "Transition")) {
        placements[componentOf(choice.key)].insert(choice.names[i]);
      }
    }
  }
  return placements;
}

TunePoint pointAt(const std::vector<Axis>& axes, uint64_t index) {
  TunePoint point;
  point.index = index;
  for (size_t a = axes.size(); a-- > 0;) {
    const uint64_t n = axes[a].placements.size();
    point.decisions[axes[a].component] = axes[a].placements[index % n];
    index /= n;
  }
  return point;
}

Expected<TuneSpace, Failure> buildTuneSpace(const std::vector<graph::Choice>& choices, const SpaceRequest& request) {
  TuneSpace space;
  // component -> the worlds it is restricted to; empty: every world. A
  // component named with several worlds keeps them all, and named without
  // one keeps every world, whatever else names it.
  std::map<std::string, std::set<std::string>> selected;
  std::set<std::string> everyWorld;
  for (const std::string& entry : request.components) {
    const size_t at = entry.find('@');
    std::set<std::string>& worlds = selected[entry.substr(0, at)];
    if (at == std::string::npos) everyWorld.insert(entry);
    if (at != std::string::npos) worlds.insert(entry.substr(at + 1));
  }
  for (const std::string& component : everyWorld) selected[component].clear();
  std::set<std::string> missing;
  for (const auto& [component, worlds] : selected) missing.insert(component);
  for (const graph::Choice& choice : choices) {
    const std::string component = componentOf(choice.key);
    if (!selected.empty() && !missing.erase(component)) continue;
    const std::set<std::string> none;
    const std::set<std::string>& onlyWorlds = selected.empty() ? none : selected.at(component);
    Axis axis{component, {}};
    const auto transitions = request.transitions.find(component);
    size_t transitionsLeftOut = 0;
    for (const std::string& name : choice.names) {
      const bool inWorld = onlyWorlds.empty() || onlyWorlds.contains(name.substr(0, name.find(':')));
      if (!inWorld || !kept(name, request.only)) continue;
      if (transitions != request.transitions.end() && transitions->second.contains(name)) {
        ++transitionsLeftOut;
        continue;
      }
      axis.placements.push_back(name);
    }
    if (axis.placements.empty() && transitionsLeftOut > 0) {
      if (selected.empty()) continue;
      return Failure{
          fmt::format("component '{}' has only level-of-detail transitions (definitions marked "
                      "[Transition]) among the requested worlds and variations, which spire-tune does "
                      "not explore",
                      component)};
    }
    if (axis.placements.empty()) {
      return Failure{
          fmt::format("component '{}' has no placement among the requested worlds and variations", component)};
    }
    space.axes.push_back(std::move(axis));
  }
  if (!missing.empty()) {
    return Failure{fmt::format("'{}' is not a choice of this shader (see spirec --choices)", *missing.begin())};
  }
  constexpr uint64_t kLimit = uint64_t{1} << 62;
  for (const Axis& axis : space.axes) {
    space.productSize =
        space.productSize > kLimit / axis.placements.size() ? kLimit : space.productSize * axis.placements.size();
  }
  if (space.productSize <= request.maxVariants) {
    for (uint64_t i = 0; i < space.productSize; ++i) space.points.push_back(pointAt(space.axes, i));
    return space;
  }
  // Sampling without replacement, in index order, so that the same request
  // always measures the same variants.
  space.sampled = true;
  std::mt19937_64 rng(request.seed);
  std::uniform_int_distribution<uint64_t> pick(0, space.productSize - 1);
  std::set<uint64_t> indices;
  while (indices.size() < request.maxVariants) indices.insert(pick(rng));
  for (uint64_t i : indices) space.points.push_back(pointAt(space.axes, i));
  return space;
}

}  // namespace spire::tune

#include "search/candidates.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>

#include "search/model_cost.h"
#include "simplify/rewrite_rules.h"
#include "simplify/rewrite_target.h"

namespace spire::search {

namespace {

std::string fromName(const std::string& component, const std::string& placement) {
  const std::string variation = variationOf(placement);
  return variation.empty() ? component : component + ":" + variation;
}

// What a selected component's current definition is, in the current level.
struct Target {
  const std::string* name = nullptr;
  std::string placement;  // the component's, in the current level
  const ast::ComponentDecl* decl = nullptr;
  std::string original;  // the variation level 0 places, which search variations grow from
};

// The components of the request to rewrite, each with its definition; a
// component the level does not compute has nothing to rewrite.
Expected<std::vector<Target>, Failure> targetsOf(const StepRequest& request) {
  const sem::Shader* shader = request.current->model().findShader(request.derived);
  if (!shader) return Failure{fmt::format("no shader named '{}'", request.derived)};
  std::vector<Target> targets;
  for (const std::string& name : request.components) {
    const sem::Component* component = shader->findComponent(name);
    Target t{&name, placementOf(request.placement, name), nullptr, variationOf(placementOf(request.original, name))};
    if (!component || t.placement.empty()) continue;
    t.decl = currentDecl(*shader, *component, t.placement);
    if (!t.decl) return Failure{fmt::format("'{}' has no definition '{}'", name, fromName(name, t.placement))};
    targets.push_back(std::move(t));
  }
  return targets;
}

// `rewrite` of the target's definition as candidate `number` of the step.
Candidate makeCandidate(const StepRequest& request, const Target& target, const simplify::Rewrite& rewrite,
                        size_t number) {
  const SourceManager& sources = request.current->sources();
  Candidate c;
  c.rewriting = {*target.name,
                 fromName(*target.name, target.placement),
                 searchVariation(target.original, "candidate", number),
                 rewrite.rule,
                 rewrite.before,
                 rewrite.replacement,
                 "",
                 {}};
  c.rewriting.text = simplify::rewrittenText(sources, *target.decl, rewrite, c.rewriting.variation);
  c.type = rewrite.type;
  c.replacementAt = simplify::replacementOffset(*target.decl, rewrite, c.rewriting.variation);
  c.level = c.rewriting;
  c.level.variation = searchVariation(target.original, "level", request.level);
  c.level.text = simplify::rewrittenText(sources, *target.decl, rewrite, c.level.variation);
  // The same rewrite is the same rewritten definition: a step that
  // changed another component leaves it, and its cached error, as it was.
  c.key = *target.name + "\n" + simplify::rewrittenText(sources, *target.decl, rewrite, "cached");
  return c;
}

}  // namespace

const ast::ComponentDecl* currentDecl(const sem::Shader& shader, const sem::Component& component,
                                      const std::string& placement) {
  const std::string variation = variationOf(placement);
  const ast::ComponentDecl* general = nullptr;
  for (const sem::Definition& d : component.definitions) {
    if (!d.decl || d.isInput() || d.variation != variation) continue;
    if (!d.world) {
      general = general ? general : d.decl;
    } else if (shader.pipeline && shader.pipeline->worlds.at(*d.world).name == worldOf(placement)) {
      return d.decl;
    }
  }
  return general;
}

std::string searchVariation(const std::string& originalVariation, const std::string& kind, size_t number) {
  return fmt::format("{}{}{}{}", originalVariation, originalVariation.empty() ? "" : "_", kind, number);
}

Expected<std::unique_ptr<ShaderLibrary>, Failure> compileModule(const ModuleCompile& compile, const std::string& path,
                                                                const std::string& text, const std::string& derived) {
  auto library = std::make_unique<ShaderLibrary>(compile.frontEnd);
  library->addSource(path, text);
  if (compile.pipelineSource && !library->addFile(*compile.pipelineSource)) {
    return Failure{fmt::format("cannot read pipeline source '{}'", *compile.pipelineSource)};
  }
  if (library->compile() && library->choiceSpace(derived) != nullptr) return library;
  for (const Diagnostic& d : library->diagnostics().all()) {
    if (d.severity == Severity::Error) return Failure{d.message};
  }
  return Failure{fmt::format("the shader '{}' was not built", derived)};
}

Expected<std::vector<Candidate>, Failure> proposeCandidates(const StepRequest& request) {
  auto targets = targetsOf(request);
  if (!targets) return targets.error();
  const std::vector<simplify::UserRule> none;
  const std::vector<simplify::UserRule>& userRules = request.userRules ? *request.userRules : none;
  std::vector<Candidate> candidates;
  for (const Target& target : *targets) {
    std::map<std::string, size_t> perRule;
    for (const simplify::Rewrite& rewrite :
         simplify::proposeRewrites(request.current->model(), request.current->sources(), *target.decl, userRules)) {
      if (++perRule[rewrite.rule] > request.k1) continue;
      candidates.push_back(makeCandidate(request, target, rewrite, candidates.size() + 1));
    }
  }
  return candidates;
}

namespace {

// The alternative of `node` in `space` to carry a component to when a move
// leaves its own one dead: of its variation, in the move's world if it can
// be, else in the latest world that can still compute it.
std::optional<graph::AltId> carriedAlternative(const graph::ChoiceSpace& space, const graph::ComponentNode& node,
                                               const std::string& variation, sem::WorldId world) {
  const graph::ShaderGraph& g = space.graph();
  std::optional<graph::AltId> best;
  for (const graph::AltId a : space.aliveAlternatives(node.id)) {
    const graph::Alternative& alt = node.alternatives[a];
    if (node.variations[alt.variation] != variation) continue;
    if (alt.world == world) return a;
    if (!best || g.worldRank(alt.world) > g.worldRank(node.alternatives[*best].world)) best = a;
  }
  return best;
}

// `placement` with `component` at `place`, and each other component kept
// where it is when some variant still allows that, else carried (a
// dependency the component no longer reads where it was); nullopt when no
// variant has the component at `place`.
std::optional<Placement> movedPlacement(const graph::ChoiceSpace& choices, const Placement& placement,
                                        const std::string& component, const std::string& place) {
  const graph::ShaderGraph& g = choices.graph();
  const auto& ids = g.shader().componentByName;
  graph::ChoiceSpace space = choices;
  const sem::ComponentId moved = ids.at(component);
  const auto alt = g.findAlternative(g.node(moved), worldOf(place), variationOf(place));
  if (!alt || !space.alive(moved, *alt) || !space.restrict(moved, *alt)) return std::nullopt;
  const sem::WorldId world = g.node(moved).alternatives[*alt].world;
  Placement result = placement;
  for (const sem::ComponentId id : g.dependencyOrder()) {
    const graph::ComponentNode& node = g.node(id);
    const auto entry =
        std::find_if(result.begin(), result.end(), [&](const auto& e) { return e.first == node.component->name; });
    if (id == moved || node.isInput || entry == result.end()) continue;
    std::optional<graph::AltId> keep = g.findAlternative(node, worldOf(entry->second), variationOf(entry->second));
    if (!keep || !space.alive(id, *keep)) keep = carriedAlternative(space, node, variationOf(entry->second), world);
    if (!keep || !space.restrict(id, *keep)) return std::nullopt;
    entry->second = g.altName(node, *keep);
  }
  for (auto& [name, where] : result) {
    if (name == component) where = place;
  }
  return result;
}

// `target`'s moves to the other worlds its definition may be placed in
// that cost less than the level, cheapest first, each with its C and its
// placement. A move that saves nothing could never make a level, and its
// error (often none) would only lower the median that K2 keeps the
// rewrites under.
std::vector<std::pair<double, Placement>> movesOf(const StepRequest& request, const Target& target,
                                                  const graph::ChoiceSpace& space,
                                                  const std::vector<graph::Choice>& choices) {
  std::vector<std::pair<double, Placement>> moves;
  const std::optional<double> current = modelCost(*request.current, request.derived, request.placement);
  if (!current) return moves;
  for (const graph::Choice& choice : choices) {
    if (space.graph().node(choice.component).component->name != *target.name) continue;
    for (const std::string& place : choice.names) {
      if (variationOf(place) != variationOf(target.placement) || worldOf(place) == worldOf(target.placement)) continue;
      std::optional<Placement> moved = movedPlacement(space, request.placement, *target.name, place);
      const std::optional<double> cost = moved ? modelCost(*request.current, request.derived, *moved) : std::nullopt;
      if (cost && *cost < *current) moves.emplace_back(*cost, std::move(*moved));
    }
  }
  std::stable_sort(moves.begin(), moves.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (moves.size() > request.k1) moves.resize(request.k1);
  return moves;
}

// The move of `target` to `moved` from the request's placement: what it
// sets, its component first, and how it reads.
Candidate moveCandidate(const StepRequest& request, const Target& target, const Placement& moved) {
  Candidate c;
  const std::string place = placementOf(moved, *target.name);
  c.rewriting = {*target.name,
                 fromName(*target.name, target.placement),
                 variationOf(target.placement),
                 kMoveRule,
                 target.placement,
                 place,
                 "",
                 {{*target.name, place}}};
  for (const auto& [name, where] : moved) {
    if (name == *target.name || placementOf(request.placement, name) == where) continue;
    c.rewriting.moved.emplace_back(name, where);
    c.rewriting.after += fmt::format(", with {} {}", name, where);
  }
  c.level = c.rewriting;
  c.key = fmt::format("{}\n{}\n{}", kMoveRule, *target.name, c.rewriting.after);
  return c;
}

}  // namespace

std::vector<Candidate> proposeMoves(const StepRequest& request) {
  auto targets = targetsOf(request);
  const graph::ChoiceSpace* space = request.current->choiceSpace(request.derived);
  if (!targets || !space) return {};
  const std::vector<graph::Choice> choices = request.current->choices(request.derived);
  std::vector<Candidate> moves;
  for (const Target& target : *targets) {
    for (const auto& [cost, moved] : movesOf(request, target, *space, choices)) {
      moves.push_back(moveCandidate(request, target, moved));
    }
  }
  return moves;
}

Expected<std::vector<AverageProbe>, Failure> proposeAverageProbes(const StepRequest& request) {
  auto targets = targetsOf(request);
  if (!targets) return targets.error();
  std::vector<AverageProbe> probes;
  for (const Target& target : *targets) {
    std::vector<simplify::AverageSite> sites =
        simplify::proposeAverageSites(request.current->model(), request.current->sources(), *target.decl);
    if (sites.size() > request.k1) sites.resize(request.k1);
    for (simplify::AverageSite& site : sites) probes.push_back({*target.name, target.placement, std::move(site)});
  }
  return probes;
}

Expected<Candidate, Failure> siteCandidate(const StepRequest& request, const AverageProbe& probe,
                                           const std::string& rule, const std::string& replacement, size_t number) {
  auto targets = targetsOf(request);
  if (!targets) return targets.error();
  for (const Target& target : *targets) {
    if (*target.name != probe.component) continue;
    simplify::Rewrite rewrite = probe.site.rewrite;
    rewrite.rule = rule;
    rewrite.replacement = "(" + replacement + ")";
    return makeCandidate(request, target, rewrite, number);
  }
  return Failure{fmt::format("'{}' is not rewritten in this step", probe.component)};
}

}  // namespace spire::search

#include "search/candidates.h"

#include <fmt/format.h>

#include <map>

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
                 ""};
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

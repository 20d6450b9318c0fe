#include "search/candidates.h"

#include <fmt/format.h>

#include <map>

#include "simplify/rewrite_rules.h"
#include "simplify/rewrite_target.h"

namespace spire::search {

namespace {

std::string placementFor(const Placement& placement, const std::string& component) {
  for (const auto& [name, place] : placement) {
    if (name == component) return place;
  }
  return {};
}

// The definition the placement computes: its variation, in its world when
// the component has a definition for that world, else the general one.
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

std::string fromName(const std::string& component, const std::string& placement) {
  const std::string variation = variationOf(placement);
  return variation.empty() ? component : component + ":" + variation;
}

}  // namespace

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
  const ShaderLibrary& library = *request.current;
  const sem::Shader* shader = library.model().findShader(request.derived);
  if (!shader) return Failure{fmt::format("no shader named '{}'", request.derived)};
  std::vector<Candidate> candidates;
  for (const std::string& name : request.components) {
    const sem::Component* component = shader->findComponent(name);
    const std::string placement = placementFor(request.placement, name);
    if (!component || placement.empty()) continue;  // not live in this variant: nothing to rewrite
    const ast::ComponentDecl* decl = currentDecl(*shader, *component, placement);
    if (!decl) return Failure{fmt::format("'{}' has no definition '{}'", name, fromName(name, placement))};
    const std::string original = variationOf(placementFor(request.original, name));
    std::map<std::string, size_t> perRule;
    const std::vector<simplify::UserRule> none;
    const std::vector<simplify::UserRule>& userRules = request.userRules ? *request.userRules : none;
    for (const simplify::Rewrite& rewrite :
         simplify::proposeRewrites(library.model(), library.sources(), *decl, userRules)) {
      if (++perRule[rewrite.rule] > request.k1) continue;
      Candidate c;
      c.rewriting = {name,
                     fromName(name, placement),
                     searchVariation(original, "candidate", candidates.size() + 1),
                     rewrite.rule,
                     rewrite.before,
                     rewrite.replacement,
                     ""};
      c.rewriting.text = simplify::rewrittenText(library.sources(), *decl, rewrite, c.rewriting.variation);
      c.type = rewrite.type;
      c.replacementAt = simplify::replacementOffset(*decl, rewrite, c.rewriting.variation);
      c.level = c.rewriting;
      c.level.variation = searchVariation(original, "level", request.level);
      c.level.text = simplify::rewrittenText(library.sources(), *decl, rewrite, c.level.variation);
      // The same rewrite is the same rewritten definition: a step that
      // changed another component leaves it, and its cached error, as it was.
      c.key = name + "\n" + simplify::rewrittenText(library.sources(), *decl, rewrite, "cached");
      candidates.push_back(std::move(c));
    }
  }
  return candidates;
}

}  // namespace spire::search

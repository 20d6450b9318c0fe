#include "driver/shader_library.h"

#include <fmt/format.h>

#include "sema/group_members.h"

namespace spire {

ShaderLibrary::ShaderLibrary(FrontEndOptions options) : frontEnd_(std::move(options)) {}

bool ShaderLibrary::compile() {
  model_ = &frontEnd_.analyze();
  DiagnosticList& diags = frontEnd_.diagnostics();
  if (diags.hasErrors()) return false;
  for (const sem::Shader* shader : graph::concreteShaders(*model_)) {
    // An optional group member's instance that fails here is left out with
    // a warning (W4101) rather than failing the library.
    sem::runMemberStage(*shader, diags, [&](DiagnosticList& stageDiags) { return addEntry(*shader, stageDiags); });
  }
  return !diags.hasErrors();
}

bool ShaderLibrary::addEntry(const sem::Shader& shader, DiagnosticList& diags) {
  auto g = graph::ShaderGraph::build(shader, diags);
  if (!g) return false;
  auto space = std::make_unique<graph::ChoiceSpace>(*g);
  if (!space->consistent()) {
    diags.report(
        DiagCode::E4017, shader.decl->nameRange,
        fmt::format("shader '{}' has no valid variant: the pipeline's requirements cannot all be met", shader.name));
    return false;
  }
  entries_.push_back({&shader, std::move(g), std::move(space)});
  return true;
}

std::vector<std::string> ShaderLibrary::shaderNames() const {
  std::vector<std::string> names;
  for (const Entry& e : entries_) names.push_back(e.shader->name);
  return names;
}

const ShaderLibrary::Entry* ShaderLibrary::find(std::string_view shader) const {
  for (const Entry& e : entries_) {
    if (e.shader->name == shader) return &e;
  }
  return nullptr;
}

const graph::ChoiceSpace* ShaderLibrary::choiceSpace(std::string_view shader) const {
  const Entry* e = find(shader);
  return e ? e->space.get() : nullptr;
}

std::vector<Choice> ShaderLibrary::choices(std::string_view shader) const {
  const Entry* e = find(shader);
  return e ? graph::enumerateChoices(*e->space) : std::vector<Choice>{};
}

std::optional<graph::Variant> ShaderLibrary::buildVariant(std::string_view shader,
                                                          const std::map<std::string, std::string>& decisions,
                                                          std::vector<std::string>* skipped,
                                                          const Attributes& attributes) const {
  const Entry* e = find(shader);
  if (!e) return std::nullopt;
  std::vector<graph::DecisionRequest> requests;
  std::vector<std::string> names;
  for (const auto& [component, placement] : decisions) {
    const auto it = e->shader->componentByName.find(component);
    std::optional<graph::AltId> alt;
    if (it != e->shader->componentByName.end()) {
      const size_t colon = placement.find(':');
      const std::string world = placement.substr(0, colon);
      const std::string variation = colon == std::string::npos ? "" : placement.substr(colon + 1);
      alt = e->graph->findAlternative(e->graph->node(it->second), world, variation);
    }
    if (!alt) {
      if (skipped) skipped->push_back(component);
      continue;
    }
    graph::DecisionRequest request{it->second, *alt, {}};
    if (const auto hints = attributes.find(component); hints != attributes.end()) request.attributes = hints->second;
    requests.push_back(std::move(request));
    names.push_back(component);
  }
  graph::VariantResult result = graph::buildVariant(*e->space, requests);
  if (skipped) {
    for (size_t i = 0; i < requests.size(); ++i) {
      if (result.outcomes[i].status != graph::DecisionStatus::Applied) skipped->push_back(names[i]);
    }
  }
  return std::move(result.variant);
}

}  // namespace spire

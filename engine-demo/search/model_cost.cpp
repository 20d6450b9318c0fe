#include "search/model_cost.h"

#include "graph/decision_file.h"
#include "simplify/variant_cost.h"

namespace spire::search {

std::optional<double> modelCost(const ShaderLibrary& library, const std::string& shader, const Placement& placement) {
  const graph::ChoiceSpace* space = library.choiceSpace(shader);
  if (!space) return std::nullopt;
  DiagnosticList diags;
  const std::optional<graph::Variant> variant =
      graph::applyDecisions(placementDecisions(shader, placement), *space, diags);
  if (!variant || diags.hasErrors()) return std::nullopt;
  return static_cast<double>(simplify::variantCost(library.model(), *variant).totalTenths()) / 10.0;
}

}  // namespace spire::search

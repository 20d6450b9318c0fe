#include "driver/definition_listing.h"

#include <fmt/format.h>

namespace spire {

std::string listDeclaredDefinitions(const sem::Model& model, std::string_view shaderFilter) {
  std::string out;
  for (const auto& shader : model.shaders) {
    if (!shaderFilter.empty() && shader->name != shaderFilter) continue;
    const sem::Pipeline& pipeline = *shader->pipeline;
    out += fmt::format("// shader {} (pipeline {})\n", shader->name, pipeline.name);
    for (const sem::Component& component : shader->components) {
      if (component.definitions.empty() || component.definitions.front().isInput()) continue;
      std::string entries;
      for (const sem::Definition& d : component.definitions) {
        if (!entries.empty()) entries += ',';
        entries += d.world ? pipeline.worlds[*d.world].name : "*";
        if (!d.variation.empty()) entries += ":" + d.variation;
      }
      const std::string& prefix = component.origin == pipeline.name ? shader->name : component.origin;
      out += fmt::format("{}.{} = {{{}}}\n", prefix, component.name, entries);
    }
  }
  return out;
}

}  // namespace spire

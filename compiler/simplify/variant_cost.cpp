#include "simplify/variant_cost.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <set>

#include "simplify/cost_model.h"

namespace spire::simplify {
namespace {

bool resamples(const sem::Import& import) {
  return import.strategy.signature && import.strategy.signature->transfer == sem::ValueTransfer::Resampled;
}

bool interpolates(const sem::Import& import) {
  return import.strategy.signature && import.strategy.signature->transfer == sem::ValueTransfer::Interpolated;
}

std::string_view rateName(WorldRate rate) {
  switch (rate) {
    case WorldRate::Vertex: return "vertex";
    case WorldRate::Fragment: return "fragment";
    default: return "other";
  }
}

std::string joined(const std::vector<std::string>& names) {
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

// What a row adds to C_v or C_f, for the table's last column.
std::string countedText(const ComponentCost& c, const VariantCost& cost) {
  std::vector<std::string> parts;
  if (c.rate == WorldRate::Vertex) parts.push_back(fmt::format("C_v += {}", c.ops));
  if (c.rate == WorldRate::Fragment) parts.push_back(fmt::format("C_f += {}", c.ops));
  for (const std::string& world : c.fetchedIn) {
    const bool vertex = std::find(cost.vertexWorlds.begin(), cost.vertexWorlds.end(), world) != cost.vertexWorlds.end();
    parts.push_back(fmt::format("{} += {} (a fetch in {})", vertex ? "C_v" : "C_f", kTextureFetchCost, world));
  }
  return parts.empty() ? "-" : fmt::format("{}", fmt::join(parts, "; "));
}

}  // namespace

std::vector<WorldRate> worldRates(const graph::ShaderGraph& graph, const codegen::StrategyRegistry& strategies) {
  const sem::Pipeline& pipeline = graph.pipeline();
  std::set<sem::WorldId> sinkWorlds;
  for (const graph::Sink& sink : graph.sinks()) sinkWorlds.insert(sink.world);
  std::vector<WorldRate> rates(pipeline.worlds.size(), WorldRate::Other);
  for (sem::WorldId w = 0; w < pipeline.worlds.size(); ++w) {
    const sem::World& world = pipeline.worlds[w];
    if (!world.isAbstract && sinkWorlds.count(w) > 0 &&
        worldStage(world, strategies) == codegen::ShaderStage::Fragment) {
      rates[w] = WorldRate::Fragment;
    }
  }
  for (const sem::Import& import : pipeline.imports) {
    const sem::World& from = pipeline.worlds[import.from];
    if (!from.isAbstract && rates[import.to] == WorldRate::Fragment && interpolates(import) &&
        worldStage(from, strategies) == codegen::ShaderStage::Vertex) {
      rates[import.from] = WorldRate::Vertex;
    }
  }
  return rates;
}

VariantCost variantCost(const sem::Model& model, const graph::Variant& variant,
                        const codegen::StrategyRegistry& strategies) {
  const graph::ShaderGraph& graph = variant.graph();
  const sem::Pipeline& pipeline = graph.pipeline();
  const std::vector<WorldRate> rates = worldRates(graph, strategies);
  VariantCost result;
  for (sem::WorldId w = 0; w < rates.size(); ++w) {
    if (rates[w] == WorldRate::Vertex) result.vertexWorlds.push_back(pipeline.worlds[w].name);
    if (rates[w] == WorldRate::Fragment) result.fragmentWorlds.push_back(pipeline.worlds[w].name);
  }
  // Texture fetches and varyings, from what each counted world imports.
  std::map<sem::ComponentId, std::vector<std::string>> fetchedIn;
  for (sem::WorldId w = 0; w < rates.size(); ++w) {
    if (rates[w] == WorldRate::Other) continue;
    int64_t& ops = rates[w] == WorldRate::Vertex ? result.vertexOps : result.fragmentOps;
    for (const graph::Transfer& t : variant.world(w).inputs) {
      const sem::Import& import = pipeline.imports[t.importIndex];
      if (resamples(import)) {
        ops += kTextureFetchCost;
        fetchedIn[t.component].push_back(pipeline.worlds[w].name);
      }
      if (rates[w] == WorldRate::Fragment && rates[import.from] == WorldRate::Vertex) {
        result.varyings += scalarCount(graph.node(t.component).component->type);
        ++result.varyingValues;
      }
    }
  }
  CostModel costs(model);
  std::map<sem::WorldId, std::set<std::string>> valuesOf;  // each world's kernel merges its equal values
  for (sem::ComponentId c : variant.live()) {
    const graph::ComponentNode& node = graph.node(c);
    const sem::WorldId world = variant.worldOf(c);
    const auto fetched = fetchedIn.find(c);
    if (node.isInput && fetched == fetchedIn.end()) continue;
    ComponentCost row{node.component->name, pipeline.worlds[world].name, rates[world], 0, {}};
    if (!node.isInput)
      row.ops = costs.sharedDefinition(*node.alternatives[*variant.choice(c)].definition->decl, valuesOf[world]);
    if (fetched != fetchedIn.end()) row.fetchedIn = fetched->second;
    if (row.rate == WorldRate::Vertex) result.vertexOps += row.ops;
    if (row.rate == WorldRate::Fragment) result.fragmentOps += row.ops;
    result.components.push_back(std::move(row));
  }
  return result;
}

std::string formatVariantCost(const VariantCost& cost, std::string_view title) {
  size_t nameWidth = std::string_view("component").size();
  size_t worldWidth = std::string_view("world").size();
  for (const ComponentCost& c : cost.components) {
    nameWidth = std::max(nameWidth, c.component.size());
    worldWidth = std::max(worldWidth, c.world.size());
  }
  std::string text = fmt::format("{}\n{:<{}}  {:<{}}  {:<8}  {:>6}  {}\n", title, "component", nameWidth, "world",
                                 worldWidth, "rate", "ops", "counted");
  for (const ComponentCost& c : cost.components) {
    text += fmt::format("{:<{}}  {:<{}}  {:<8}  {:>6}  {}\n", c.component, nameWidth, c.world, worldWidth,
                        rateName(c.rate), c.ops, countedText(c, cost));
  }
  const int64_t tenths = cost.totalTenths();
  text += fmt::format("\nC_v   = {} (vertex rate: {})\n", cost.vertexOps, joined(cost.vertexWorlds));
  text += fmt::format("C_f   = {} (fragment rate: {})\n", cost.fragmentOps, joined(cost.fragmentWorlds));
  text += fmt::format("N_var = {} (scalars of {} value(s) passed from vertex to fragment rate)\n", cost.varyings,
                      cost.varyingValues);
  text += fmt::format("C     = 0.3 * {} + 0.7 * {} + 10 * {} = {}.{}\n", cost.vertexOps, cost.fragmentOps,
                      cost.varyings, tenths / 10, tenths % 10);
  return text;
}

}  // namespace spire::simplify

#include "sema/strategy_catalog.h"

namespace spire::sem {

const StrategyCatalog& StrategyCatalog::builtin() {
  static const StrategyCatalog catalog = [] {
    StrategyCatalog c;
    c.add({"uniformImport", StrategyRole::Import, {}, "std140 uniform block"});
    c.add({"standardImport", StrategyRole::Import, {}, "'in' variables matching the producer's 'out'"});
    c.add({"textureImport", StrategyRole::Import, {{"uv", "vec2"}}, "one sampler per component, fetched at uv"});
    c.add({"bufferImport", StrategyRole::Import, {}, "std430 storage buffer read at the invocation index"});
    c.add({"standardExport", StrategyRole::Export, {}, "'out' variables"});
    c.add({"vertexExport", StrategyRole::Export, {{"position", "vec4"}}, "'out' variables plus gl_Position"});
    c.add({"bufferExport", StrategyRole::Export, {}, "std430 storage buffer written per invocation"});
    return c;
  }();
  return catalog;
}

void StrategyCatalog::add(StrategySignature signature) {
  std::string key = signature.name;
  strategies_.insert_or_assign(std::move(key), std::move(signature));
}

const StrategySignature* StrategyCatalog::find(std::string_view name) const {
  auto it = strategies_.find(name);
  return it == strategies_.end() ? nullptr : &it->second;
}

std::vector<std::string_view> StrategyCatalog::names(StrategyRole role) const {
  std::vector<std::string_view> result;
  for (const auto& [name, sig] : strategies_) {
    if (sig.role == role) result.push_back(name);
  }
  return result;
}

std::string_view roleName(StrategyRole role) { return role == StrategyRole::Import ? "import" : "export"; }

}  // namespace spire::sem

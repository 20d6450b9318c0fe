// Strategies by name. The built-in registry holds the paper's seven; an
// embedding application may add its own before compiling.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "codegen/strategy.h"
#include "sema/strategy_catalog.h"

namespace spire::codegen {

class StrategyRegistry {
 public:
  // A registry with the built-in strategies.
  static StrategyRegistry withBuiltins();
  // The shared built-in registry.
  static const StrategyRegistry& builtin();

  // Adds or replaces the strategy with the same name.
  void add(std::unique_ptr<Strategy> strategy);
  const Strategy* find(std::string_view name) const;
  // The names and parameters sema checks pipelines against.
  const sem::StrategyCatalog& catalog() const { return catalog_; }

 private:
  std::map<std::string, std::unique_ptr<Strategy>, std::less<>> strategies_;
  sem::StrategyCatalog catalog_;
};

// The pipeline stage `world`'s kernel runs in: its [Stage] attribute, or
// else what its export strategy implies (vertexExport: vertex, ...);
// nullopt when neither says.
std::optional<ShaderStage> worldStage(const sem::World& world, const StrategyRegistry& strategies);

}  // namespace spire::codegen

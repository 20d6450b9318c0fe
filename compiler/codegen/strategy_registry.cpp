#include "codegen/strategy_registry.h"

namespace spire::codegen {

#define SPIRE_STRATEGY(factory) std::unique_ptr<Strategy> factory();
#include "codegen/strategies/builtin_strategies.def"
#undef SPIRE_STRATEGY

StrategyRegistry StrategyRegistry::withBuiltins() {
  StrategyRegistry registry;
#define SPIRE_STRATEGY(factory) registry.add(factory());
#include "codegen/strategies/builtin_strategies.def"
#undef SPIRE_STRATEGY
  return registry;
}

const StrategyRegistry& StrategyRegistry::builtin() {
  static const StrategyRegistry registry = withBuiltins();
  return registry;
}

void StrategyRegistry::add(std::unique_ptr<Strategy> strategy) {
  catalog_.add(strategy->signature());
  const std::string name = strategy->signature().name;
  strategies_.insert_or_assign(name, std::move(strategy));
}

const Strategy* StrategyRegistry::find(std::string_view name) const {
  auto it = strategies_.find(name);
  return it == strategies_.end() ? nullptr : it->second.get();
}

// Sema's attribute check has refused any [Stage] value parseStage does not
// know.
std::optional<ShaderStage> worldStage(const sem::World& world, const StrategyRegistry& strategies) {
  for (const ast::Attribute& a : world.decl->attributes) {
    if (a.name == "Stage" && a.value) return reflection::parseStage(*a.value);
  }
  const Strategy* exportStrategy = world.exportStrategy ? strategies.find(world.exportStrategy->ref->name) : nullptr;
  return exportStrategy ? exportStrategy->stage() : std::nullopt;
}

}  // namespace spire::codegen

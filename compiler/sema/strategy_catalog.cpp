#include "sema/strategy_catalog.h"

namespace spire::sem {

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

std::string_view transferName(ValueTransfer transfer) {
  switch (transfer) {
    case ValueTransfer::Exact: return "exact";
    case ValueTransfer::Interpolated: return "interpolated";
    case ValueTransfer::Resampled: return "resampled";
    case ValueTransfer::Aggregated: return "aggregated";
  }
  return "exact";
}

}  // namespace spire::sem

// The names and parameter lists of the import/export strategies a pipeline may
// use. Sema checks pipelines against this catalogue; codegen's
// StrategyRegistry builds it from the strategies it holds, so each strategy
// declares its signature once, next to its code.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace spire::sem {

enum class StrategyRole : uint8_t { Import, Export };

struct StrategyParam {
  std::string name;      // for messages: "uv"
  std::string typeName;  // GLSL type the argument expression must have: "vec2"
};

struct StrategySignature {
  std::string name;
  StrategyRole role = StrategyRole::Import;
  std::vector<StrategyParam> params;
  std::string summary;  // one line for docs and "did you mean" notes
};

class StrategyCatalog {
 public:
  void add(StrategySignature signature);
  const StrategySignature* find(std::string_view name) const;
  // Names of strategies with the given role, sorted.
  std::vector<std::string_view> names(StrategyRole role) const;

 private:
  std::map<std::string, StrategySignature, std::less<>> strategies_;
};

std::string_view roleName(StrategyRole role);

}  // namespace spire::sem

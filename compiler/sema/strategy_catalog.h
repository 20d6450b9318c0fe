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

// What an import does to the values it carries when the producer is a world
// that computes (an import from an abstract world hands over the engine's
// values as they are). Routing prefers routes that change values least, in
// this order, so that no declaration order can send a value through a world
// that averages or resamples it when a faithful route exists.
enum class ValueTransfer : uint8_t {
  Exact,         // each consumer invocation reads the producer's value for it (bufferImport)
  Interpolated,  // blended between producer invocations by the rasterizer (standardImport)
  Resampled,     // stored at one rate and filtered at another (textureImport)
  Aggregated,    // many producer invocations reduced to one value (uniformImport)
};

struct StrategySignature {
  std::string name;
  StrategyRole role = StrategyRole::Import;
  std::vector<StrategyParam> params;
  std::string summary;                            // one line for docs and "did you mean" notes
  ValueTransfer transfer = ValueTransfer::Exact;  // imports only
  // Imports: reads `in` variables at locations; exports: writes `out`
  // variables at locations. Two kernels linked this way must agree on every
  // location (codegen's interface allocation).
  bool usesLocations = false;
  // Imports only: can hand over opaque values (samplers) from an abstract
  // world. No export strategy writes them, so an opaque value is available
  // only in the worlds that import it this way directly from its world.
  bool carriesOpaque = false;
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
std::string_view transferName(ValueTransfer transfer);

}  // namespace spire::sem

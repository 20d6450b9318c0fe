// standardImport: `in` variables at the locations the producer gave its
// `out` variables (vertex attributes when the producer is the mesh).
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class StandardImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }

  Expected<void, Failure> emitImport(ImportSite& site) const override {
    KernelBuilder& kernel = site.consumer;
    if (kernel.stage() == ShaderStage::Compute) {
      return Failure{
          fmt::format("standardImport cannot feed world '{}': a compute kernel has no 'in' variables; use "
                      "bufferImport",
                      kernel.world())};
    }
    for (const KernelValue& v : site.values) {
      if (auto checked = checkVarying(v, "standardImport"); !checked) return checked;
      const uint32_t location = site.producerLocation(v.component);
      const bool flat = kernel.stage() == ShaderStage::Fragment && needsFlat(v.type);
      kernel.declare(fmt::format("layout(location = {}) {}in {};", location, flat ? "flat " : "",
                                 kernel.declaration(v.type, v.glslName)));
      reflection::KernelInput entry = importEntry(site, v, reflection::InputKind::Varying, "standardImport");
      entry.location = location;
      kernel.reflectInput(std::move(entry));
    }
    return {};
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("standardImport", sem::StrategyRole::Import, {}, "'in' variables matching the producer's 'out'",
                    sem::ValueTransfer::Interpolated, true);
};

}  // namespace

std::unique_ptr<Strategy> makeStandardImport() { return std::make_unique<StandardImport>(); }

}  // namespace spire::codegen

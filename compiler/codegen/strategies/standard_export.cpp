// standardExport: `out` variables (fragment outputs, or varyings).
#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class StandardExport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }
  std::optional<ShaderStage> stage() const override { return ShaderStage::Fragment; }
  Expected<void, Failure> emitExport(ExportSite& site) const override {
    return emitOutVariables(site, "standardExport");
  }

 private:
  sem::StrategySignature signature_ = makeSignature("standardExport", sem::StrategyRole::Export, {}, "'out' variables",
                                                    sem::ValueTransfer::Exact, true);
};

}  // namespace

std::unique_ptr<Strategy> makeStandardExport() { return std::make_unique<StandardExport>(); }

}  // namespace spire::codegen
